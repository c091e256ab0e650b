// insertVertices: points added to a constrained Delaunay TIN keep it constrained Delaunay, on
// the paper's distributions, on constrained edges of a grid (cocircular everywhere), and at a
// 1e6 offset.

#include "terratin/constrain/constrained_validation.hpp"
#include "terratin/constrain/insert_constraints.hpp"

#include "constraint_checks.hpp"
#include "point_distributions.hpp"
#include "terratin/error.hpp"
#include "terratin/triangulate/triangulate.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

namespace terratin {
namespace {

using test::Distribution;

void expectValid(const ConstrainedTin& tin) {
    const ConstrainedValidation validation = validateConstrainedDelaunay(tin);
    EXPECT_TRUE(validation.ok()) << (validation.problems.empty() ? "" : validation.problems[0]);
}

/// The centroids of every `step`-th triangle: points strictly inside the hull.
std::vector<Point3> centroids(const TinMesh& mesh, std::size_t step) {
    std::vector<Point3> points;
    for (std::size_t t = 0; t < mesh.triangleCount(); t += step) {
        Point3 sum{0.0, 0.0, 0.0};
        for (std::size_t i = 0; i < 3; ++i) {
            const Point3& corner = mesh.vertices[mesh.triangles[3 * t + i]];
            sum = {sum.x + corner.x / 3, sum.y + corner.y / 3, sum.z + corner.z / 3};
        }
        points.push_back(sum);
    }
    return points;
}

class InsertVerticesDistribution : public ::testing::TestWithParam<Distribution> {};

TEST_P(InsertVerticesDistribution, StaysConstrainedDelaunay_WithCrossingConstraints) {
    const TinMesh mesh = triangulate(test::generatePoints(GetParam(), 2000, 7)).mesh;
    ConstraintSet constraints;
    constraints.segments = test::randomSegments(mesh.vertexCount(), 60, 11);
    ConstrainedTin tin = insertConstraints(mesh, constraints);
    const std::vector<Point3> points = centroids(tin.mesh, 5);
    const std::vector<std::uint32_t> sources(points.size(), 123456);
    const std::size_t before = tin.mesh.vertexCount();
    EXPECT_EQ(insertVertices(tin, points, sources), points.size());
    EXPECT_EQ(tin.mesh.vertexCount(), before + points.size());
    EXPECT_EQ(tin.mesh.sourceIndex.back(), 123456U);
    expectValid(tin);
}

INSTANTIATE_TEST_SUITE_P(Distributions, InsertVerticesDistribution,
                         ::testing::ValuesIn(bench::kAllDistributions));

/// An n x n grid of unit spacing at `offset`, a row constrained from end to end.
struct GridWithRow {
    TinMesh mesh;
    ConstrainedTin tin;
};

GridWithRow gridWithRow(int n, int row, double offset) {
    std::vector<Point3> points;
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x)
            points.push_back({offset + x, offset + y, double(x * y)});
    GridWithRow grid{triangulate(points).mesh, {}};
    ConstraintSet constraints;
    constraints.polylines.push_back(
        {{offset, offset + row, 0.0}, {offset + n - 1, offset + row, 0.0}});
    grid.tin = insertConstraints(grid.mesh, constraints);
    return grid;
}

TEST(InsertVertices, APointOnAConstrainedEdgeSplitsIt_AndItsChainGetsThePoint) {
    for (const double offset : {0.0, 1e6}) {
        GridWithRow grid = gridWithRow(12, 4, offset);
        const std::size_t chainBefore = grid.tin.chains[0].size();
        std::vector<Point3> onRow;
        for (int x = 0; x + 1 < 12; x += 2)
            onRow.push_back({offset + x + 0.5, offset + 4, 50.0});
        const std::vector<std::uint32_t> sources(onRow.size(), 9);
        EXPECT_EQ(insertVertices(grid.tin, onRow, sources), onRow.size());
        EXPECT_EQ(grid.tin.chains[0].size(), chainBefore + onRow.size());
        for (std::size_t j = 1; j < grid.tin.chains[0].size(); ++j)
            EXPECT_TRUE(test::hasConstrainedEdge(grid.tin, grid.tin.chains[0][j - 1],
                                                 grid.tin.chains[0][j]));
        expectValid(grid.tin);
    }
}

TEST(InsertVertices, APointOnAVertexIsSkipped_AndOneOutsideIsRefused) {
    GridWithRow grid = gridWithRow(6, 2, 0.0);
    const std::vector<Point3> onVertex = {{3.0, 3.0, 99.0}};
    const std::vector<std::uint32_t> source = {1};
    EXPECT_EQ(insertVertices(grid.tin, onVertex, source), 0U);
    EXPECT_EQ(grid.tin.mesh.vertexCount(), 36U);
    const std::vector<Point3> outside = {{2.5, 2.5, 0.0}, {7.0, 1.0, 0.0}};
    const std::vector<std::uint32_t> sources = {1, 2};
    EXPECT_THROW((void)insertVertices(grid.tin, outside, sources), InvalidInputError);
    EXPECT_EQ(grid.tin.mesh.vertexCount(), 37U); // the point before the bad one went in
    expectValid(grid.tin);
    EXPECT_THROW((void)insertVertices(grid.tin, outside, source), InvalidInputError);
}

TEST(InsertVertices, StartingTrianglesGiveTheSameTin) {
    const TinMesh mesh = triangulate(test::generatePoints(Distribution::Gauss, 3000, 9)).mesh;
    ConstraintSet constraints;
    constraints.segments = test::randomSegments(mesh.vertexCount(), 40, 4);
    const ConstrainedTin constrained = insertConstraints(mesh, constraints);
    const std::vector<Point3> points = centroids(constrained.mesh, 31);
    const std::vector<std::uint32_t> sources(points.size(), 1);
    std::vector<std::uint32_t> near; // the triangle each centroid came from
    for (std::size_t t = 0; t < constrained.mesh.triangleCount(); t += 31)
        near.push_back(static_cast<std::uint32_t>(t));
    ConstrainedTin walked = constrained;
    ConstrainedTin started = constrained;
    EXPECT_EQ(insertVertices(walked, points, sources), points.size());
    EXPECT_EQ(insertVertices(started, points, sources, nullptr, near), points.size());
    expectValid(started);
    EXPECT_EQ(walked.mesh.vertexCount(), started.mesh.vertexCount());
    EXPECT_EQ(walked.mesh.triangleCount(), started.mesh.triangleCount());
    const std::vector<std::uint32_t> outOfRange = {
        static_cast<std::uint32_t>(started.mesh.triangleCount())};
    EXPECT_THROW((void)insertVertices(started, std::span(points).first(1),
                                      std::span(sources).first(1), nullptr, outOfRange),
                 InvalidInputError);
}

TEST(InsertVertices, ChangedTrianglesAreAllThatDiffer) {
    const TinMesh mesh = triangulate(test::generatePoints(Distribution::Uniform, 3000, 5)).mesh;
    ConstraintSet constraints;
    constraints.segments = test::randomSegments(mesh.vertexCount(), 40, 2);
    ConstrainedTin tin = insertConstraints(mesh, constraints);
    const TinMesh before = tin.mesh;
    const std::vector<Point3> points = centroids(tin.mesh, 97);
    const std::vector<std::uint32_t> sources(points.size(), 1);
    std::vector<std::uint8_t> changed;
    (void)insertVertices(tin, points, sources, &changed);
    ASSERT_EQ(changed.size(), tin.mesh.triangleCount());
    std::size_t differing = 0;
    for (std::size_t t = 0; t < tin.mesh.triangleCount(); ++t) {
        const bool same =
            t < before.triangleCount() &&
            std::equal(before.triangles.begin() + 3 * t, before.triangles.begin() + 3 * t + 3,
                       tin.mesh.triangles.begin() + 3 * t);
        differing += same ? 0 : 1;
        if (!same) {
            EXPECT_EQ(changed[t], 1) << t;
        }
    }
    EXPECT_GE(differing, 3 * points.size()); // each point makes at least three triangles
    EXPECT_LT(std::count(changed.begin(), changed.end(), 1), tin.mesh.triangleCount() / 2);
}

} // namespace
} // namespace terratin

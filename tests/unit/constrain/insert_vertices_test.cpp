// insertVertices: points added to a constrained Delaunay TIN keep it constrained Delaunay, on
// the paper's distributions, on constrained edges of a grid (cocircular everywhere), and at a
// 1e6 offset; in bands on the threads, the same TIN as in order, and the same for any threads.

#include "terratin/constrain/constrained_validation.hpp"
#include "terratin/constrain/insert_constraints.hpp"

#include "constraint_checks.hpp"
#include "point_distributions.hpp"
#include "terratin/error.hpp"
#include "terratin/triangulate/triangulate.hpp"
#include "zoned_vertices.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <set>
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

/// The grid's points for the bands: the centroid of every other triangle, and the middle of
/// every edge of the constrained row (refused by the bands: the chain is shared), each with
/// the triangle it lies in or on.
struct BandPoints {
    std::vector<Point3> points;
    std::vector<std::uint32_t> near;
};

BandPoints bandPoints(const ConstrainedTin& tin, int n, int row, double offset) {
    BandPoints band;
    const TinMesh& mesh = tin.mesh;
    for (std::size_t t = 0; t < mesh.triangleCount(); t += 2) {
        Point3 sum{0.0, 0.0, 0.0};
        for (std::size_t i = 0; i < 3; ++i) {
            const Point3& corner = mesh.vertices[mesh.triangles[3 * t + i]];
            sum = {sum.x + corner.x / 3, sum.y + corner.y / 3, sum.z + corner.z / 3};
        }
        band.points.push_back(sum);
        band.near.push_back(static_cast<std::uint32_t>(t));
    }
    for (std::size_t h = 0; h < mesh.triangles.size(); ++h) {
        const Point3& a = mesh.vertices[mesh.triangles[h]];
        const Point3& b = mesh.vertices[mesh.triangles[h % 3 == 2 ? h - 2 : h + 1]];
        if (tin.constrained[h] != 0 && a.y == offset + row && a.x < b.x && b.x - a.x == 1.0) {
            band.points.push_back({a.x + 0.5, a.y, -1.0});
            band.near.push_back(static_cast<std::uint32_t>(h / 3));
        }
    }
    EXPECT_EQ(band.points.size(), mesh.triangleCount() / 2 + n - 1);
    return band;
}

/// The TIN's triangles as sets of corner coordinates: the same TIN whatever the numbering.
std::set<std::array<double, 6>> triangleShapes(const TinMesh& mesh) {
    std::set<std::array<double, 6>> shapes;
    for (std::size_t t = 0; t < mesh.triangleCount(); ++t) {
        std::array<std::array<double, 2>, 3> corners;
        for (std::size_t i = 0; i < 3; ++i) {
            const Point3& p = mesh.vertices[mesh.triangles[3 * t + i]];
            corners[i] = {p.x, p.y};
        }
        std::sort(corners.begin(), corners.end());
        shapes.insert({corners[0][0], corners[0][1], corners[1][0], corners[1][1], corners[2][0],
                       corners[2][1]});
    }
    return shapes;
}

void expectSameArrays(const ConstrainedTin& a, const ConstrainedTin& b) {
    EXPECT_EQ(a.mesh.vertices.size(), b.mesh.vertices.size());
    EXPECT_TRUE(std::equal(a.mesh.vertices.begin(), a.mesh.vertices.end(), b.mesh.vertices.begin(),
                           b.mesh.vertices.end(), [](const Point3& p, const Point3& q) {
                               return p.x == q.x && p.y == q.y && p.z == q.z;
                           }));
    EXPECT_TRUE(std::equal(a.mesh.triangles.begin(), a.mesh.triangles.end(),
                           b.mesh.triangles.begin(), b.mesh.triangles.end()));
    EXPECT_TRUE(std::equal(a.mesh.neighbours.begin(), a.mesh.neighbours.end(),
                           b.mesh.neighbours.begin(), b.mesh.neighbours.end()));
    EXPECT_TRUE(std::equal(a.mesh.sourceIndex.begin(), a.mesh.sourceIndex.end(),
                           b.mesh.sourceIndex.begin(), b.mesh.sourceIndex.end()));
    EXPECT_EQ(a.constrained, b.constrained);
    EXPECT_EQ(a.chains, b.chains);
}

TEST_P(InsertVerticesDistribution, InBands_TheSameTinAsInOrder_AndTheSameForAnyThreads) {
    const TinMesh mesh = triangulate(test::generatePoints(GetParam(), 6000, 3)).mesh;
    ConstraintSet constraints;
    constraints.segments = test::randomSegments(mesh.vertexCount(), 60, 8);
    const ConstrainedTin constrained = insertConstraints(mesh, constraints);
    const std::vector<Point3> points = centroids(constrained.mesh, 1);
    std::vector<std::uint32_t> near(points.size());
    for (std::size_t t = 0; t < near.size(); ++t)
        near[t] = static_cast<std::uint32_t>(t);
    ASSERT_GT(detail::vertexZoneCount(points.size()), 1U);
    const std::vector<std::uint32_t> sources(points.size(), 3);
    ConstrainedTin inOrder = constrained;
    const std::size_t inserted = insertVertices(inOrder, points, sources);
    std::vector<ConstrainedTin> banded;
    for (const unsigned threads : {1U, 2U, 4U}) {
        ConstrainedTin& tin = banded.emplace_back(constrained);
        EXPECT_EQ(insertVertices(tin, points, sources, nullptr, near, threads), inserted);
    }
    expectValid(banded.front());
    EXPECT_EQ(triangleShapes(banded.front().mesh), triangleShapes(inOrder.mesh));
    for (std::size_t k = 1; k < banded.size(); ++k)
        expectSameArrays(banded[k], banded.front());
}

TEST(InsertVertices, InBandsOnAGrid_TheSameTinAsInOrder_AndTheSameForAnyThreads) {
    constexpr int kSide = 90;
    constexpr int kRow = 41;
    for (const double offset : {0.0, 1e6}) {
        const GridWithRow grid = gridWithRow(kSide, kRow, offset);
        const BandPoints band = bandPoints(grid.tin, kSide, kRow, offset);
        ASSERT_GT(detail::vertexZoneCount(band.points.size()), 1U);
        const std::vector<std::uint32_t> sources(band.points.size(), 77);

        ConstrainedTin inOrder = grid.tin; // without triangles to start from: no bands
        const std::size_t inserted = insertVertices(inOrder, band.points, sources);
        EXPECT_EQ(inserted, band.points.size());
        std::vector<ConstrainedTin> banded;
        std::vector<std::vector<std::uint8_t>> changed;
        for (const unsigned threads : {1U, 2U, 4U}) {
            ConstrainedTin& tin = banded.emplace_back(grid.tin);
            EXPECT_EQ(insertVertices(tin, band.points, sources, &changed.emplace_back(), band.near,
                                     threads),
                      inserted);
        }
        const ConstrainedTin& tin = banded.front();
        expectValid(tin);
        EXPECT_EQ(triangleShapes(tin.mesh), triangleShapes(inOrder.mesh));
        ASSERT_EQ(tin.chains.size(), 1U);
        EXPECT_EQ(tin.chains[0].size(), static_cast<std::size_t>(2 * kSide - 1));
        for (std::size_t j = 1; j < tin.chains[0].size(); ++j) {
            const Point3& a = tin.mesh.vertices[tin.chains[0][j - 1]];
            const Point3& b = tin.mesh.vertices[tin.chains[0][j]];
            EXPECT_EQ(b.x - a.x, 0.5);
            EXPECT_EQ(b.y, offset + kRow);
            EXPECT_TRUE(test::hasConstrainedEdge(tin, tin.chains[0][j - 1], tin.chains[0][j]));
        }
        for (std::size_t t = 0; t < grid.tin.mesh.triangleCount(); ++t)
            if (!std::equal(grid.tin.mesh.triangles.begin() + 3 * t,
                            grid.tin.mesh.triangles.begin() + 3 * t + 3,
                            tin.mesh.triangles.begin() + 3 * t)) {
                EXPECT_EQ(changed[0][t], 1) << t;
            }
        EXPECT_EQ(changed[0].size(), tin.mesh.triangleCount());
        for (std::size_t k = 1; k < banded.size(); ++k) {
            expectSameArrays(banded[k], tin);
            EXPECT_EQ(changed[k], changed[0]);
        }
    }
}

TEST(InsertVertices, InBands_APointOutsideTheHullIsRefused_AndTheTinStaysWhole) {
    const GridWithRow grid = gridWithRow(80, 30, 0.0);
    BandPoints band = bandPoints(grid.tin, 80, 30, 0.0);
    band.points.push_back({100.0, 40.0, 0.0});
    band.near.push_back(0);
    const std::vector<std::uint32_t> sources(band.points.size(), 5);
    ConstrainedTin tin = grid.tin;
    EXPECT_THROW((void)insertVertices(tin, band.points, sources, nullptr, band.near, 2),
                 InvalidInputError);
    EXPECT_GT(tin.mesh.vertexCount(), grid.tin.mesh.vertexCount());
    for (const Point3& p : tin.mesh.vertices)
        EXPECT_TRUE(std::isfinite(p.x)); // no slot of the bands left open
    expectValid(tin);
}

INSTANTIATE_TEST_SUITE_P(Distributions, InsertVerticesDistribution,
                         ::testing::ValuesIn(bench::kAllDistributions));

} // namespace
} // namespace terratin

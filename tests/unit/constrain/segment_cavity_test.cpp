#include "segment_cavity.hpp"

#include "constraint_checks.hpp"
#include "point_distributions.hpp"
#include "terratin/constrain/constrained_validation.hpp"
#include "terratin/triangulate/triangulate.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <stdexcept>
#include <string>
#include <tuple>
#include <vector>

namespace terratin::detail {
namespace {

using test::Distribution;
using Triangle = std::array<std::uint32_t, 3>;

// The triangles as corner triples, each turned to start at its smallest corner, sorted: the
// same set for the same triangulation however its triangles are numbered.
std::vector<Triangle> triangleSet(const TinMesh& mesh) {
    std::vector<Triangle> triangles;
    for (std::size_t t = 0; t < mesh.triangleCount(); ++t) {
        Triangle corners = {mesh.triangles[3 * t], mesh.triangles[3 * t + 1],
                            mesh.triangles[3 * t + 2]};
        std::rotate(corners.begin(), std::min_element(corners.begin(), corners.end()),
                    corners.end());
        triangles.push_back(corners);
    }
    std::sort(triangles.begin(), triangles.end());
    return triangles;
}

std::uint32_t vertexAt(const TinMesh& mesh, double x, double y) {
    for (std::size_t v = 0; v < mesh.vertexCount(); ++v)
        if (mesh.vertices[v].x == x && mesh.vertices[v].y == y)
            return static_cast<std::uint32_t>(v);
    throw std::logic_error("no vertex at (" + std::to_string(x) + ", " + std::to_string(y) + ")");
}

// The walk from u towards v as the inserter makes it; false when the segment starts along an
// edge or meets a constrained edge (the inserter's other cases).
bool walkFrom(const CdtMesh& mesh, std::uint32_t u, std::uint32_t v, CrossedEdges& crossed) {
    const SegmentStart start = findSegmentStart(mesh, u, v);
    return start.kind == SegmentStart::Kind::IntoTriangle &&
           walkCrossedEdges(mesh, u, v, start, crossed) == kNoHalfEdge;
}

class SegmentCavityDistribution
    : public ::testing::TestWithParam<std::tuple<Distribution, std::size_t>> {};

// The constrained Delaunay triangulation is unique (incircleTieBroken breaks every cocircular
// tie), so retriangulating the crossed region must give the triangles the flips give.
TEST_P(SegmentCavityDistribution, GivesTheTrianglesOfTheFlips) {
    const auto [distribution, count] = GetParam();
    const TinMesh original = triangulate(test::generatePoints(distribution, count, 11)).mesh;
    CdtMesh byCavity(original);
    CdtMesh byFlips(original);
    CavityScratch scratch;
    ConstrainedTin tin;
    std::size_t retriangulated = 0;
    for (const auto& [u, v] : test::randomSegments(original.vertexCount(), 60, 23)) {
        CrossedEdges crossedA;
        CrossedEdges crossedB;
        if (u == v || !walkFrom(byCavity, u, v, crossedA))
            continue;
        ASSERT_TRUE(walkFrom(byFlips, u, v, crossedB));
        std::size_t segment = retriangulateCavity(byCavity, u, crossedA, scratch);
        if (segment == kNoHalfEdge)
            segment = flipSegmentIn(byCavity, u, crossedA);
        else
            ++retriangulated;
        ASSERT_EQ(byCavity.from(segment), u);
        ASSERT_EQ(byCavity.to(segment), crossedA.end);
        byCavity.setConstrained(segment, true);
        flipSegmentIn(byFlips, u, crossedB);
        ASSERT_EQ(triangleSet(byCavity.mesh()), triangleSet(byFlips.mesh()))
            << "after segment " << u << " -> " << crossedA.end;
        tin.chains.push_back({u, crossedA.end});
    }
    EXPECT_GT(retriangulated, 0U);
    tin.mesh = byCavity.takeMesh();
    tin.constrained = byCavity.takeFlags();
    const ConstrainedValidation validation = validateConstrainedDelaunay(tin);
    EXPECT_TRUE(validation.ok()) << (validation.problems.empty() ? "" : validation.problems[0]);
}

INSTANTIATE_TEST_SUITE_P(
    PaperDistributions, SegmentCavityDistribution,
    ::testing::Combine(::testing::Values(Distribution::Uniform, Distribution::Gauss,
                                         Distribution::Cluster, Distribution::Grid,
                                         Distribution::Arc),
                       ::testing::Values(std::size_t{200}, std::size_t{3000})),
    [](const auto& paramInfo) {
        return test::toString(std::get<0>(paramInfo.param)) + "_" +
               std::to_string(std::get<1>(paramInfo.param));
    });

// The configuration of InsertConstraints.RegressionSegmentCrossingEveryTriangleAroundAVertex:
// the segment y = 0.1 passes (0, 0) on both sides of its triangles, so (0, 0) comes twice in
// the chain below; the region beside it is no polygon and is left to the flips.
TEST(SegmentCavity, ChangesNothing_WhenTheSegmentPassesAVertexTwice) {
    const std::vector<Point3> points = {{0, 0, 0},   {0, -1, 0},   {1, 0.5, 0},
                                        {0, 1, 0},   {-1, 0.5, 0}, {-2, 0.1, 0},
                                        {2, 0.1, 0}, {0, -3, 0},   {0, 3, 0}};
    const TinMesh original = triangulate(points).mesh;
    CdtMesh mesh(original);
    CrossedEdges crossed;
    CavityScratch scratch;
    const std::uint32_t u = vertexAt(original, -2, 0.1);
    ASSERT_TRUE(walkFrom(mesh, u, vertexAt(original, 2, 0.1), crossed));
    EXPECT_EQ(retriangulateCavity(mesh, u, crossed, scratch), kNoHalfEdge);
    EXPECT_EQ(mesh.mesh().triangles, original.triangles);
    EXPECT_EQ(mesh.mesh().neighbours, original.neighbours);
}

TEST(SegmentCavity, ChangesNothing_WhenTheSegmentCrossesMoreThanTheMostEdges) {
    // A row of kMaxCavityCrossings + 1 columns of a grid between two points off it: the
    // segment along the row crosses every column's vertical edges.
    std::vector<Point3> points;
    const int columns = static_cast<int>(kMaxCavityCrossings) + 4;
    for (int y = 0; y < 2; ++y)
        for (int x = 0; x < columns; ++x)
            points.push_back({double(x), double(y), 0.0});
    points.push_back({-1.0, 0.5, 0.0});
    points.push_back({double(columns), 0.5, 0.0});
    const TinMesh original = triangulate(points).mesh;
    CdtMesh mesh(original);
    CrossedEdges crossed;
    CavityScratch scratch;
    const std::uint32_t u = vertexAt(original, -1.0, 0.5);
    ASSERT_TRUE(walkFrom(mesh, u, vertexAt(original, double(columns), 0.5), crossed));
    ASSERT_GT(crossed.edges.size(), kMaxCavityCrossings);
    EXPECT_EQ(retriangulateCavity(mesh, u, crossed, scratch), kNoHalfEdge);
    EXPECT_EQ(mesh.mesh().triangles, original.triangles);
}

TEST(SegmentCavity, KeepsTheFlagOfAConstrainedEdgeOnTheBoundary) {
    // A 4 x 4 grid with its edge (1, 1)-(1, 2) constrained; the segment from (1.5, -1) to
    // (1.6, 2.5) crosses the cell right of that edge through the triangle holding it.
    std::vector<Point3> points;
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 4; ++x)
            points.push_back({double(x), double(y), 0.0});
    points.push_back({1.5, -1.0, 0.0});
    points.push_back({1.6, 2.5, 0.0});
    const TinMesh original = triangulate(points).mesh;
    CdtMesh mesh(original);
    const std::uint32_t low = vertexAt(original, 1, 1);
    const std::uint32_t high = vertexAt(original, 1, 2);
    const std::size_t edge = mesh.findEdge(low, high);
    ASSERT_NE(edge, kNoHalfEdge);
    mesh.setConstrained(edge, true);
    CrossedEdges crossed;
    CavityScratch scratch;
    const std::uint32_t u = vertexAt(original, 1.5, -1.0);
    ASSERT_TRUE(walkFrom(mesh, u, vertexAt(original, 1.6, 2.5), crossed));
    const auto crossedTriangle = [&](std::size_t h) {
        return h / 3 == crossed.edges.front().hint / 3 ||
               std::any_of(crossed.entries.begin(), crossed.entries.end(),
                           [&](std::size_t entry) { return entry / 3 == h / 3; });
    };
    ASSERT_TRUE(crossedTriangle(edge) || crossedTriangle(mesh.twin(edge)));
    const std::size_t segment = retriangulateCavity(mesh, u, crossed, scratch);
    ASSERT_NE(segment, kNoHalfEdge);
    mesh.setConstrained(segment, true);
    const std::size_t kept = mesh.findEdge(low, high);
    ASSERT_NE(kept, kNoHalfEdge);
    EXPECT_TRUE(mesh.isConstrained(kept));
    ConstrainedTin tin;
    tin.chains = {{low, high}, {u, crossed.end}};
    tin.mesh = mesh.takeMesh();
    tin.constrained = mesh.takeFlags();
    const ConstrainedValidation validation = validateConstrainedDelaunay(tin);
    EXPECT_TRUE(validation.ok()) << (validation.problems.empty() ? "" : validation.problems[0]);
}

TEST(CdtMesh, ReplaceCavity_Throws_WhenANewEdgeIsNotOnTheBoundary) {
    const std::vector<Point3> points = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
    const TinMesh original = triangulate(points).mesh;
    CdtMesh mesh(original);
    const std::vector<std::size_t> slots = {0, 1};
    const std::vector<std::size_t> boundary = {0, 1, 2, 3};
    constexpr std::uint32_t kBoundary = CdtMesh::CavityTriangle::kCavityBoundary;
    // Two triangles that claim the first four half-edges in an order that does not fit.
    const std::vector<CdtMesh::CavityTriangle> triangles = {
        {{0, 2, 1}, {kBoundary | 3, kBoundary | 2, 1}},
        {{0, 3, 2}, {kBoundary | 1, kBoundary | 0, 0}}};
    EXPECT_THROW(mesh.replaceCavity(slots, boundary, triangles), std::logic_error);
    EXPECT_EQ(mesh.mesh().triangles, original.triangles);
}

} // namespace
} // namespace terratin::detail

#include "zoned_insertion.hpp"

#include "constraint_checks.hpp"
#include "point_distributions.hpp"
#include "terratin/triangulate/triangulate.hpp"

#include <gtest/gtest.h>

#include <string>
#include <tuple>
#include <vector>

namespace terratin {
namespace {

using test::Distribution;

// An n x n grid of unit spacing, z = x - y.
TinMesh gridMesh(int n) {
    std::vector<Point3> points;
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x)
            points.push_back({double(x), double(y), double(x - y)});
    return triangulate(points).mesh;
}

// insertInZones in two bands on two threads on `mesh`: each polyline's segments numbered after
// the previous polyline's (firstOwner), each polyline's vertices in `vertices`.
struct TwoZones {
    explicit TwoZones(const TinMesh& mesh) : inserter(mesh, 64) {}
    detail::ZonedInsertion run(const ConstraintSet& constraints) {
        std::uint32_t owners = 0;
        for (const std::vector<Point3>& polyline : constraints.polylines) {
            firstOwner.push_back(owners);
            owners += static_cast<std::uint32_t>(polyline.size() - 1);
        }
        inserter.prepareChains(owners);
        vertices.assign(constraints.polylines.size(), {});
        return detail::insertInZones(inserter, constraints, 2, 2, firstOwner, vertices);
    }
    detail::ConstraintInserter inserter;
    std::vector<std::uint32_t> firstOwner;
    std::vector<std::vector<std::uint32_t>> vertices;
};

class ZonedInsertionDistribution
    : public ::testing::TestWithParam<std::tuple<Distribution, unsigned>> {};

// The zones' views of one mesh change it on several threads: the TIN is constrained Delaunay,
// and the same, array for array, for 1, 2 and 4 threads.
TEST_P(ZonedInsertionDistribution, IsConstrainedDelaunay_AndTheSameForAnyNumberOfThreads) {
    const auto [distribution, zones] = GetParam();
    const TinMesh mesh = triangulate(test::generatePoints(distribution, 4000, 11)).mesh;
    ConstraintSet constraints = test::walksWithTriangles(mesh, 80, 40, 3);
    ASSERT_GT(constraints.polylines.size(), 20U);
    constraints.zones = zones;
    constraints.threads = 1;
    const ConstrainedTin one = insertConstraints(mesh, constraints);
    test::expectConstrainedDelaunay(one, mesh, constraints);
    for (const unsigned threads : {2U, 4U}) {
        constraints.threads = threads;
        const ConstrainedTin many = insertConstraints(mesh, constraints);
        EXPECT_EQ(many.mesh.vertices, one.mesh.vertices) << threads << " threads";
        EXPECT_EQ(many.mesh.triangles, one.mesh.triangles) << threads << " threads";
        EXPECT_EQ(many.mesh.neighbours, one.mesh.neighbours) << threads << " threads";
        EXPECT_EQ(many.constrained, one.constrained) << threads << " threads";
        EXPECT_EQ(many.chains, one.chains) << threads << " threads";
        EXPECT_EQ(many.intersections, one.intersections) << threads << " threads";
    }
}

TEST_P(ZonedInsertionDistribution, IsConstrainedDelaunay_WhenOffsetByAMillion) {
    const auto [distribution, zones] = GetParam();
    const TinMesh unit = triangulate(test::generatePoints(distribution, 2000, 5)).mesh;
    ConstraintSet walks = test::walksWithTriangles(unit, 40, 30, 9);
    std::vector<std::vector<Point3>> lines;
    for (const std::vector<Point3>& polyline : walks.polylines)
        lines.push_back(test::offset(polyline, 1.0e6, 5.0e6));
    const TinMesh mesh =
        triangulate(test::offset(test::generatePoints(distribution, 2000, 5), 1.0e6, 5.0e6)).mesh;
    ConstraintSet constraints = test::locatedPolylines(mesh, lines);
    constraints.zones = zones;
    constraints.threads = 2;
    test::expectConstrainedDelaunay(insertConstraints(mesh, constraints), mesh, constraints);
}

INSTANTIATE_TEST_SUITE_P(
    PaperDistributions, ZonedInsertionDistribution,
    ::testing::Combine(::testing::Values(Distribution::Uniform, Distribution::Gauss,
                                         Distribution::Cluster, Distribution::Grid,
                                         Distribution::Arc),
                       ::testing::Values(2U, 4U)),
    [](const auto& paramInfo) {
        return test::toString(std::get<0>(paramInfo.param)) + "_" +
               std::to_string(std::get<1>(paramInfo.param)) + "zones";
    });

// Polylines along a grid's lines and diagonals (cocircular everywhere, segments through
// vertices) in four zones.
TEST(ZonedInsertion, GridLinePolylinesAreConstrainedDelaunay) {
    const int n = 41;
    const TinMesh mesh = gridMesh(n);
    std::vector<std::vector<Point3>> lines;
    for (int k = 1; k < n - 1; k += 3) {
        lines.push_back({{double(k), 0, 0}, {double(k), double(n - 1), 0}});
        lines.push_back({{double(k) + 0.5, 0.5, 0}, {double(k) + 0.5, 20, 0}, {39.5, 30.25, 0}});
    }
    ConstraintSet constraints = test::locatedPolylines(mesh, lines);
    constraints.zones = 4;
    constraints.threads = 4;
    const ConstrainedTin tin = insertConstraints(mesh, constraints);
    test::expectConstrainedDelaunay(tin, mesh, constraints);
    EXPECT_EQ(tin.chains[0].size(), std::size_t(n)); // every vertex of the column
    EXPECT_GT(tin.intersections, 0U);
}

// The zones insert the polylines that keep to their zone, and refuse, leaving for afterwards,
// those that reach across the border between them (in both rounds: bands of x, then of y).
TEST(ZonedInsertion, ZonesInsertThePolylinesInsideThem_AndRefuseThoseAcrossTheBorder) {
    const TinMesh mesh = gridMesh(41);
    std::vector<std::vector<Point3>> lines;
    for (int k = 0; k < 16; ++k) {
        const double y = 2.25 + 2.0 * k;
        const double x = k % 2 == 0 ? 2.5 : 22.5;
        lines.push_back({{x, y, 0}, {x + 6.0, y + 0.5, 0}, {x + 14.0, y + 0.75, 0}});
    }
    // Its first point puts the border between the zones at x = 20.5; it reaches across.
    lines.push_back({{20.5, 1.25, 0}, {6.5, 38.5, 0}});
    const ConstraintSet constraints = test::locatedPolylines(mesh, lines);
    TwoZones zones(mesh);
    const detail::ZonedInsertion zoned = zones.run(constraints);
    ASSERT_EQ(zoned.refused.size(), 1U);
    EXPECT_EQ(zoned.refused.front().polyline, 16U);
    for (std::size_t k = 0; k < 16; ++k)
        EXPECT_EQ(zones.vertices[k].size(), 3U) << "polyline " << k;
}

// Polylines that all stop at the edge of the first round's bands of x (their first points
// lie on it) go on in the second round's bands of y: each keeps to its band but one, whose
// first point sets the bands' border.
TEST(ZonedInsertion, PolylinesStoppedAtABandsEdge_GoOnInBandsOfY) {
    const TinMesh mesh = gridMesh(41);
    std::vector<std::vector<Point3>> lines;
    for (int k = 0; k < 8; ++k) {
        std::vector<Point3> line;
        for (int j = 0; j < 8; ++j)
            line.push_back({2.5 + 5.0 * j, 3.5 + 4.5 * k, 0});
        lines.push_back(line);
    }
    const ConstraintSet constraints = test::locatedPolylines(mesh, lines);
    detail::ConstraintInserter inserter(mesh, 64);
    std::vector<std::uint32_t> firstOwner;
    for (std::uint32_t k = 0; k < 8; ++k)
        firstOwner.push_back(7 * k);
    inserter.prepareChains(56);
    std::vector<std::vector<std::uint32_t>> vertices(8);
    const detail::ZonedInsertion zoned =
        detail::insertInZones(inserter, constraints, 2, 2, firstOwner, vertices);
    ASSERT_EQ(zoned.refused.size(), 1U);
    EXPECT_EQ(zoned.refused.front().polyline, 4U); // at y = 21.5, the border
    for (std::size_t k = 0; k < 8; ++k)
        if (k != 4) {
            EXPECT_EQ(vertices[k].size(), 8U) << "polyline " << k;
        }
}

// A zone that refuses a polyline's point has put in the segments between the points before
// it, while the mesh there was in cache, rather than leave the whole polyline's segments to the
// next round.
TEST(ZonedInsertion, ARefusedPointsPolyline_HasItsSegmentsBeforeThePointIn) {
    const TinMesh mesh = gridMesh(21);
    const std::vector<std::vector<Point3>> lines{
        {{2.5, 4.25, 0}, {6.5, 5.75, 0}, {10.5, 4.25, 0}, {15.5, 5.75, 0}}};
    const ConstraintSet constraints = test::locatedPolylines(mesh, lines);
    ASSERT_EQ(constraints.polylines.front().size(), 4U);
    detail::ConstraintInserter shared(mesh, 8);
    shared.prepareChains(3);
    const auto [vertexSlots, triangleSlots] = shared.appendSlots(16, 32);
    const detail::Zone zone{false, -100.0, 12.0};
    detail::ConstraintInserter inZone(shared, zone, vertexSlots, triangleSlots, 3);
    // As zoneStarts gives them: the last point's triangle has no corner in the zone.
    std::vector<std::uint32_t> starts = constraints.polylineTriangles.front();
    starts.back() = kFromPreviousPoint;
    detail::PolylineProgress progress;
    std::vector<std::uint32_t> vertices;
    EXPECT_THROW(detail::insertPolyline(inZone, constraints, vertices, 0, progress, starts),
                 detail::ZoneRefusal);
    EXPECT_EQ(progress.nextPoint, 3U);
    EXPECT_EQ(progress.nextSegment, 3U);
    ASSERT_EQ(vertices.size(), 3U);
    for (std::size_t j = 1; j < 3; ++j) {
        const std::size_t edge = inZone.mesh().findEdge(vertices[j - 1], vertices[j]);
        ASSERT_NE(edge, detail::kNoHalfEdge) << "segment " << j;
        EXPECT_TRUE(inZone.mesh().isConstrained(edge)) << "segment " << j;
        EXPECT_EQ(shared.chainOf(static_cast<std::uint32_t>(j - 1)),
                  (std::vector<std::uint32_t>{vertices[j - 1], vertices[j]}))
            << "segment " << j;
    }
}

// A polyline a zone refused crosses, when it goes in afterwards on one thread, a constrained
// edge a zone made: the crossing's vertex is inserted by the mesh itself, which has no slots
// of a zone to run out of (it refused, and the refusal escaped).
TEST(ZonedInsertion, RegressionRefusedPolylineCrossesAZonesConstrainedEdge) {
    const TinMesh mesh = gridMesh(21);
    const std::vector<std::vector<Point3>> lines{
        {{1.5, 10.25, 0}, {18.5, 10.25, 0}}, // zone 0, across the border: refused
        {{5.5, 1.5, 0}, {6.5, 1.5, 0}},      // sets the border at x = 5.5
        {{15.5, 0.5, 0}, {15.5, 19.5, 0}}};  // zone 1, crossed by the first
    ConstraintSet constraints = test::locatedPolylines(mesh, lines);
    constraints.zones = 2;
    constraints.threads = 2;
    const ConstrainedTin tin = insertConstraints(mesh, constraints);
    test::expectConstrainedDelaunay(tin, mesh, constraints);
    EXPECT_EQ(tin.intersections, 1U);
}

// The second round's zones split the first round's constrained edges where their polylines
// cross them (both ends of the edge in the zone): the crossings no longer leave the polylines
// for afterwards, on one thread. Here only the polyline whose first point sets the second
// round's border is left; the TIN is constrained Delaunay with the four crossings in the chains.
TEST(ZonedInsertion, SecondRoundSplitsTheFirstRoundsEdges_InsteadOfRefusingThePolylines) {
    const TinMesh mesh = gridMesh(41);
    std::vector<Point3> left;
    std::vector<Point3> right;
    for (double y = 2.5; y <= 20.5; y += 2.0) {
        left.push_back({30.5, y, 0});
        right.push_back({34.5, y, 0});
    }
    const std::vector<std::vector<Point3>> lines{
        {{2.5, 5.25, 0}, {37.5, 5.25, 0}},   // stopped at x = 20.5, goes on below y = 10.5
        {{2.5, 15.25, 0}, {37.5, 15.25, 0}}, // the same above it
        {{20.5, 10.5, 0}, {21.5, 10.5, 0}},  // sets both borders; refused by both rounds
        left,                                // the first round's, right of x = 20.5
        right};
    const ConstraintSet constraints = test::locatedPolylines(mesh, lines);
    TwoZones zones(mesh);
    const detail::ZonedInsertion zoned = zones.run(constraints);
    ASSERT_EQ(zoned.refused.size(), 1U);
    EXPECT_EQ(zoned.refused.front().polyline, 2U);
    EXPECT_EQ(zones.vertices[0].size(), 2U);
    EXPECT_EQ(zones.vertices[1].size(), 2U);
    // Each crossing's vertex is in the chains of both segments it splits.
    for (const std::uint32_t owner : {zones.firstOwner[0], zones.firstOwner[1]})
        EXPECT_EQ(zones.inserter.chainOf(owner).size(), 4U) << "segment " << owner;

    for (const unsigned threads : {1U, 2U}) {
        ConstraintSet whole = constraints;
        whole.zones = 2;
        whole.threads = threads;
        const ConstrainedTin tin = insertConstraints(mesh, whole);
        test::expectConstrainedDelaunay(tin, mesh, whole);
        EXPECT_EQ(tin.intersections, 4U) << threads << " threads";
    }
}

} // namespace
} // namespace terratin

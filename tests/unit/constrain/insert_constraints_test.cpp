#include "terratin/constrain/insert_constraints.hpp"

#include "constraint_checks.hpp"
#include "point_distributions.hpp"
#include "terratin/error.hpp"
#include "terratin/geometry/predicates.hpp"
#include "terratin/triangulate/tin_locator.hpp"
#include "terratin/triangulate/triangulate.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>
#include <string_view>
#include <tuple>

namespace terratin {
namespace {

using test::Distribution;

TinMesh delaunayOf(const std::vector<Point3>& points) {
    return triangulate(points).mesh;
}

ConstrainedTin constrainAndCheck(const TinMesh& mesh, const ConstraintSet& constraints) {
    ConstrainedTin tin = insertConstraints(mesh, constraints);
    test::expectConstrainedDelaunay(tin, mesh, constraints);
    return tin;
}

// The vertex at exactly (x, y).
std::uint32_t vertexAt(const TinMesh& mesh, double x, double y) {
    for (std::size_t v = 0; v < mesh.vertexCount(); ++v)
        if (mesh.vertices[v].x == x && mesh.vertices[v].y == y)
            return static_cast<std::uint32_t>(v);
    ADD_FAILURE() << "no vertex at (" << x << ", " << y << ")";
    return 0;
}

// An n x n grid of unit spacing, z = x + 2y.
std::vector<Point3> grid(int n) {
    std::vector<Point3> points;
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x)
            points.push_back({double(x), double(y), double(x + 2 * y)});
    return points;
}

class ConstrainDistribution
    : public ::testing::TestWithParam<std::tuple<Distribution, std::size_t>> {};

TEST_P(ConstrainDistribution, IsConstrainedDelaunay_WithRandomCrossingSegments) {
    const auto [distribution, count] = GetParam();
    const TinMesh mesh = delaunayOf(test::generatePoints(distribution, count, 42));
    ConstraintSet constraints;
    constraints.segments = test::randomSegments(mesh.vertexCount(), count / 10 + 5, 3);
    const ConstrainedTin tin = constrainAndCheck(mesh, constraints);
    // Random chords of an arc may miss each other; random segments elsewhere cross.
    if (distribution != Distribution::Arc) {
        EXPECT_GT(tin.intersections, 0U);
    }
}

TEST_P(ConstrainDistribution, IsConstrainedDelaunay_WhenOffsetByAMillion) {
    const auto [distribution, count] = GetParam();
    const TinMesh mesh =
        delaunayOf(test::offset(test::generatePoints(distribution, count, 7), 1.0e6, 5.0e6));
    ConstraintSet constraints;
    constraints.segments = test::randomSegments(mesh.vertexCount(), count / 10 + 5, 5);
    constrainAndCheck(mesh, constraints);
}

TEST_P(ConstrainDistribution, IsConstrainedDelaunay_WithRandomPolylines) {
    const auto [distribution, count] = GetParam();
    const TinMesh mesh = delaunayOf(test::generatePoints(distribution, count, 9));
    // Polylines through points drawn inside the hull: convex combinations of two vertices,
    // moved a tenth of the way towards the vertices' centroid to stay clear of the hull.
    const auto ends = test::randomSegments(mesh.vertexCount(), 3 * (count / 50 + 2), 17);
    Point2 centroid;
    for (const Point3& p : mesh.vertices) {
        centroid.x += p.x / double(mesh.vertexCount());
        centroid.y += p.y / double(mesh.vertexCount());
    }
    ConstraintSet constraints;
    for (std::size_t k = 0; k + 2 < ends.size(); k += 3) {
        std::vector<Point3> polyline;
        for (std::size_t j = 0; j < 3; ++j) {
            const Point3& a = mesh.vertices[ends[k + j][0]];
            const Point3& b = mesh.vertices[ends[k + j][1]];
            polyline.push_back({0.9 * (0.25 * a.x + 0.75 * b.x) + 0.1 * centroid.x,
                                0.9 * (0.25 * a.y + 0.75 * b.y) + 0.1 * centroid.y, 1.0});
        }
        constraints.polylines.push_back(polyline);
    }
    constrainAndCheck(mesh, constraints);
}

INSTANTIATE_TEST_SUITE_P(
    PaperDistributions, ConstrainDistribution,
    ::testing::Combine(::testing::Values(Distribution::Uniform, Distribution::Gauss,
                                         Distribution::Cluster, Distribution::Grid,
                                         Distribution::Arc),
                       ::testing::Values(std::size_t{100}, std::size_t{3000})),
    [](const auto& paramInfo) {
        return test::toString(std::get<0>(paramInfo.param)) + "_" +
               std::to_string(std::get<1>(paramInfo.param));
    });

TEST(InsertConstraints, ChainPassesThroughVerticesOnTheSegment) {
    const TinMesh mesh = delaunayOf(grid(6));
    ConstraintSet constraints;
    constraints.segments = {{vertexAt(mesh, 0, 0), vertexAt(mesh, 5, 5)}};
    const ConstrainedTin tin = constrainAndCheck(mesh, constraints);
    ASSERT_EQ(tin.chains[0].size(), 6U);
    for (std::size_t k = 0; k < 6; ++k)
        EXPECT_EQ(tin.chains[0][k], vertexAt(mesh, double(k), double(k)));
    EXPECT_EQ(tin.addedPoints + tin.intersections, 0U);
}

TEST(InsertConstraints, CrossingSegmentsGetAVertexWithZAlongTheFirst) {
    const TinMesh mesh = delaunayOf(grid(5));
    ConstraintSet constraints;
    // (0, 1) -> (4, 2) first, then (1, 4) -> (2, 0): they cross off every grid point.
    const std::uint32_t a = vertexAt(mesh, 0, 1);
    const std::uint32_t b = vertexAt(mesh, 4, 2);
    constraints.segments = {{a, b}, {vertexAt(mesh, 1, 4), vertexAt(mesh, 2, 0)}};
    const ConstrainedTin tin = constrainAndCheck(mesh, constraints);
    ASSERT_EQ(tin.intersections, 1U);
    const std::uint32_t crossing = static_cast<std::uint32_t>(mesh.vertexCount());
    EXPECT_EQ(tin.mesh.sourceIndex[crossing], kIntersectionSource);
    const Point3& p = tin.mesh.vertices[crossing];
    // Exact crossing: (0, 1) + s (4, 1) = (1, 4) + r (1, -4) gives s = 7/17.
    EXPECT_NEAR(p.x, 28.0 / 17.0, 1e-14);
    EXPECT_NEAR(p.y, 1.0 + 7.0 / 17.0, 1e-14);
    const Point3& pa = mesh.vertices[a];
    const Point3& pb = mesh.vertices[b];
    EXPECT_NEAR(p.z, pa.z + 7.0 / 17.0 * (pb.z - pa.z), 1e-13);
    for (const auto& chain : tin.chains)
        EXPECT_NE(std::find(chain.begin(), chain.end(), crossing), chain.end());
}

// The documented rounding: the crossing vertex lies within a few units in the last place of
// both segments' lines (its distance, not its orientation sign, is what rounding bounds).
TEST(InsertConstraints, CrossingVertexLiesWithinUlpsOfBothSegments_WhenOffsetByAMillion) {
    const TinMesh mesh =
        delaunayOf(test::offset(test::generatePoints(Distribution::Uniform, 400, 5), 1e6, 5e6));
    ConstraintSet constraints;
    constraints.segments = test::randomSegments(mesh.vertexCount(), 40, 23);
    const ConstrainedTin tin = constrainAndCheck(mesh, constraints);
    ASSERT_GT(tin.intersections, 0U);
    const double ulp = 5e6 * std::numeric_limits<double>::epsilon();
    for (std::size_t k = 0; k < constraints.segments.size(); ++k) {
        const Point3& a = tin.mesh.vertices[constraints.segments[k][0]];
        const Point3& b = tin.mesh.vertices[constraints.segments[k][1]];
        const double length = std::hypot(b.x - a.x, b.y - a.y);
        for (const std::uint32_t v : tin.chains[k]) {
            const Point3& p = tin.mesh.vertices[v];
            const double cross = (b.x - a.x) * (p.y - a.y) - (b.y - a.y) * (p.x - a.x);
            EXPECT_LE(std::fabs(cross) / length, 4 * ulp) << "constraint " << k;
        }
    }
}

TEST(InsertConstraints, OverlappingCollinearSegmentsShareEdges) {
    const TinMesh mesh = delaunayOf(grid(8));
    ConstraintSet constraints;
    const auto at = [&](double x, double y) { return vertexAt(mesh, x, y); };
    // Along one row: 0..4 and 2..7 overlap on 2..4; 1..3 lies inside 0..4; 5..7 is repeated
    // backwards; and a diagonal through the same vertices.
    constraints.segments = {{at(0, 3), at(4, 3)},
                            {at(2, 3), at(7, 3)},
                            {at(1, 3), at(3, 3)},
                            {at(7, 3), at(5, 3)},
                            {at(0, 0), at(6, 6)}};
    const ConstrainedTin tin = constrainAndCheck(mesh, constraints);
    EXPECT_EQ(tin.chains[0].size(), 5U);
    EXPECT_EQ(tin.chains[1].size(), 6U);
    EXPECT_EQ(tin.chains[3].size(), 3U);
    EXPECT_EQ(tin.addedPoints + tin.intersections, 0U);
}

TEST(InsertConstraints, DuplicateAndReversedSegmentsGiveTheSameChain) {
    const TinMesh mesh = delaunayOf(test::generatePoints(Distribution::Uniform, 500, 4));
    ConstraintSet constraints;
    constraints.segments = test::randomSegments(mesh.vertexCount(), 10, 8);
    for (std::size_t k = 0; k < 10; ++k) {
        constraints.segments.push_back(constraints.segments[k]);
        constraints.segments.push_back({constraints.segments[k][1], constraints.segments[k][0]});
    }
    const ConstrainedTin tin = constrainAndCheck(mesh, constraints);
    for (std::size_t k = 0; k < 10; ++k) {
        EXPECT_EQ(tin.chains[10 + 2 * k], tin.chains[k]);
        EXPECT_EQ(std::vector<std::uint32_t>(tin.chains[11 + 2 * k].rbegin(),
                                             tin.chains[11 + 2 * k].rend()),
                  tin.chains[k]);
    }
}

TEST(InsertConstraints, ZeroLengthSegmentsAreIgnored) {
    const TinMesh mesh = delaunayOf(grid(4));
    ConstraintSet constraints;
    constraints.segments = {{5, 5}};
    constraints.polylines = {{{1.5, 1.5, 0}, {1.5, 1.5, 0}}};
    const ConstrainedTin tin = constrainAndCheck(mesh, constraints);
    EXPECT_EQ(tin.chains[0], std::vector<std::uint32_t>{5});
    EXPECT_EQ(tin.chains[1].size(), 1U);
    EXPECT_EQ(std::count(tin.constrained.begin(), tin.constrained.end(), 1), 0);
}

TEST(InsertConstraints, ClosedRingIsAClosedChain) {
    const TinMesh mesh = delaunayOf(test::generatePoints(Distribution::Uniform, 2000, 6));
    std::vector<Point3> ring;
    for (int k = 0; k < 24; ++k) {
        const double angle = 2 * 3.141592653589793 * k / 24;
        ring.push_back({0.5 + 0.3 * std::cos(angle), 0.5 + 0.3 * std::sin(angle), 2.0});
    }
    ring.push_back(ring.front());
    ConstraintSet constraints;
    constraints.polylines = {ring};
    const ConstrainedTin tin = constrainAndCheck(mesh, constraints);
    EXPECT_EQ(tin.chains[0].front(), tin.chains[0].back());
    EXPECT_EQ(tin.addedPoints, 24U);
}

TEST(InsertConstraints, PolylinePointOnAVertexUsesIt) {
    const TinMesh mesh = delaunayOf(grid(5));
    ConstraintSet constraints;
    constraints.polylines = {{{1, 1, 99}, {3, 2, 99}, {3.5, 0.5, 99}}};
    const ConstrainedTin tin = constrainAndCheck(mesh, constraints);
    EXPECT_EQ(tin.chains[0].front(), vertexAt(mesh, 1, 1));
    EXPECT_EQ(tin.mesh.vertices[tin.chains[0].front()].z, 3.0); // keeps its own elevation
    EXPECT_EQ(tin.addedPoints, 1U);
    EXPECT_EQ(tin.mesh.vertices[tin.chains[0].back()].z, 99.0);
}

// Every third row and column of a grid (cocircular everywhere), crossing at grid points, and
// diagonals crossing those lines between grid points.
TEST(InsertConstraints, GridLinesOfARegularGrid) {
    const int n = 31;
    const TinMesh mesh = delaunayOf(grid(n));
    ConstraintSet constraints;
    for (int k = 0; k < n; k += 3) {
        constraints.segments.push_back({vertexAt(mesh, 0, k), vertexAt(mesh, n - 1, k)});
        constraints.segments.push_back({vertexAt(mesh, k, 0), vertexAt(mesh, k, n - 1)});
    }
    constraints.segments.push_back({vertexAt(mesh, 0, 1), vertexAt(mesh, n - 1, 12)});
    constraints.segments.push_back({vertexAt(mesh, 2, n - 1), vertexAt(mesh, 17, 0)});
    const ConstrainedTin tin = constrainAndCheck(mesh, constraints);
    EXPECT_EQ(tin.chains[0].size(), std::size_t(n));
    EXPECT_GT(tin.intersections, 0U);
}

// A DEM's grid lines at UTM-like coordinates: x = 1e6 + 0.1 i is not exact, so the posts of
// a row are collinear only up to rounding, and rows cross columns a rounding away from posts.
TEST(InsertConstraints, GridLinesOfARegularGrid_WhenOffsetByAMillion) {
    const int n = 21;
    std::vector<Point3> points;
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i)
            points.push_back({1e6 + 0.1 * i, 5e6 + 0.1 * j, double(i)});
    const TinMesh mesh = delaunayOf(points);
    ConstraintSet constraints;
    const auto post = [&](int i, int j) { return vertexAt(mesh, 1e6 + 0.1 * i, 5e6 + 0.1 * j); };
    for (int k = 0; k < n; k += 4) {
        constraints.segments.push_back({post(0, k), post(n - 1, k)});
        constraints.segments.push_back({post(k, 0), post(k, n - 1)});
    }
    constraints.segments.push_back({post(0, 0), post(n - 1, n - 1)});
    constrainAndCheck(mesh, constraints);
}

TEST(InsertConstraints, ThreeSegmentsThroughOnePoint) {
    const TinMesh mesh = delaunayOf(grid(5));
    ConstraintSet constraints;
    // All three pass through (2, 2.25), between the grid's vertices; the vertical one also
    // through the grid's vertices (2, 0) to (2, 4).
    constraints.polylines = {
        {{0.5, 0.5, 0}, {3.5, 4, 0}}, {{0.5, 4, 0}, {3.5, 0.5, 0}}, {{2, 0, 0}, {2, 4, 0}}};
    const ConstrainedTin tin = constrainAndCheck(mesh, constraints);
    EXPECT_GE(tin.intersections, 1U);
}

// Regression: the segment y = 0.1 crosses all four triangles around (0, 0), which puts that
// vertex inside the crossed region; the first version retriangulated that region as two
// pseudo-polygons, which assume no vertex inside, and broke the neighbour links.
TEST(InsertConstraints, RegressionSegmentCrossingEveryTriangleAroundAVertex) {
    const std::vector<Point3> points = {{0, 0, 0},   {0, -1, 0},   {1, 0.5, 0},
                                        {0, 1, 0},   {-1, 0.5, 0}, {-2, 0.1, 0},
                                        {2, 0.1, 0}, {0, -3, 0},   {0, 3, 0}};
    const TinMesh mesh = delaunayOf(points);
    const std::uint32_t centre = vertexAt(mesh, 0, 0);
    std::size_t around = 0;
    for (std::size_t t = 0; t < mesh.triangleCount(); ++t) {
        bool hasCentre = false;
        bool above = false;
        for (std::size_t i = 0; i < 3; ++i) {
            hasCentre = hasCentre || mesh.triangles[3 * t + i] == centre;
            above = above || mesh.vertices[mesh.triangles[3 * t + i]].y > 0.1;
        }
        if (hasCentre) {
            ++around;
            EXPECT_TRUE(above) << "triangle " << t << " around (0, 0) is not crossed";
        }
    }
    EXPECT_EQ(around, 4U);
    ConstraintSet constraints;
    constraints.segments = {{vertexAt(mesh, -2, 0.1), vertexAt(mesh, 2, 0.1)}};
    const ConstrainedTin tin = constrainAndCheck(mesh, constraints);
    EXPECT_EQ(tin.chains[0].size(), 2U);
}

// Lines through one point: the first crossing makes a vertex, the others pass within
// rounding of it and go through it rather than making vertices a rounding away.
TEST(InsertConstraints, LinesThroughOnePointShareOneCrossingVertex) {
    const TinMesh mesh = delaunayOf(test::generatePoints(Distribution::Uniform, 2000, 21));
    ConstraintSet constraints;
    for (int k = 0; k < 30; ++k) {
        const double angle = 3.141592653589793 * k / 30 + 0.1;
        const double dx = 0.3 * std::cos(angle);
        const double dy = 0.3 * std::sin(angle);
        constraints.polylines.push_back({{0.5 + dx, 0.5 + dy, 0}, {0.5 - dx, 0.5 - dy, 0}});
    }
    const ConstrainedTin tin = constrainAndCheck(mesh, constraints);
    EXPECT_EQ(tin.intersections, 1U);
}

// Sixty lines through the middle of a Gauss cloud: they cross within a few ulps of one another.
std::vector<std::vector<Point3>> linesThroughTheMiddle(const TinMesh& mesh, double angleOffset) {
    double cx = 0.0;
    double cy = 0.0;
    for (const Point3& p : mesh.vertices) {
        cx += p.x / double(mesh.vertexCount());
        cy += p.y / double(mesh.vertexCount());
    }
    std::vector<std::vector<Point3>> lines;
    for (int k = 0; k < 60; ++k) {
        const double angle = 3.14159265358979 * k / 60 + angleOffset;
        const double dx = 0.15 * std::cos(angle);
        const double dy = 0.15 * std::sin(angle);
        lines.push_back({{cx + dx, cy + dy, 1}, {cx - dx, cy - dy, 1}});
    }
    return lines;
}

// Regression: a crossing a rounding beyond an earlier one once made a segment run to it and
// back, and reading the chains back by following edges then failed ("a constraint's edges do
// not form a chain").
TEST(InsertConstraints, RegressionChainsThroughACrowdOfCrossings) {
    const TinMesh mesh = delaunayOf(test::generatePoints(Distribution::Gauss, 300, 6));
    ConstraintSet constraints;
    constraints.polylines = linesThroughTheMiddle(mesh, 0.06);
    const ConstrainedTin tin = constrainAndCheck(mesh, constraints);
    EXPECT_LT(tin.intersections, 60U); // many lines go through an earlier crossing's vertex
    const Point3& a = constraints.polylines[0][0];
    const Point3& b = constraints.polylines[0][1];
    for (std::size_t v = mesh.vertexCount(); v < tin.mesh.vertexCount(); ++v)
        if (tin.mesh.sourceIndex[v] == kIntersectionSource) {
            const Point3& p = tin.mesh.vertices[v];
            EXPECT_LT(std::hypot(p.x - (a.x + b.x) / 2, p.y - (a.y + b.y) / 2), 1e-14)
                << "crossing vertex " << v << " strays from the lines' common point";
        }
}

// Regression: in such a crowd, a crossing rounded onto the end of the segment being inserted,
// the crossed constraint was re-inserted through it and rounded back onto its old edge, which
// crossed the segment again: the insertion never ended.
TEST(InsertConstraints, RegressionCrowdOfCrossingsDoesNotLoop) {
    const TinMesh mesh = delaunayOf(test::generatePoints(Distribution::Gauss, 5000, 10));
    ConstraintSet constraints;
    constraints.polylines = linesThroughTheMiddle(mesh, 0.1);
    constrainAndCheck(mesh, constraints);
}

// `count` lines between vertices of a Uniform cloud drawn at random: about a quarter of the
// pairs cross, so a few hundred lines make tens of thousands of crossings.
ConstraintSet crossingLines(const TinMesh& mesh, std::size_t count, std::uint64_t seed) {
    ConstraintSet constraints;
    for (const auto& [a, b] : test::randomSegments(mesh.vertexCount(), count, seed))
        constraints.polylines.push_back({mesh.vertices[a], mesh.vertices[b]});
    return constraints;
}

// The progress callback is polled all along the insertion of many crossing lines, most of whose
// work is their crossings, and a false answer ends it at once: no further call, Cancelled thrown
// though most lines are still to go in.
TEST(InsertConstraints, ACancelDuringManyCrossingLines_ThrowsCancelledAtTheCallThatSaidStop) {
    const TinMesh mesh = delaunayOf(test::generatePoints(Distribution::Uniform, 3000, 31));
    const ConstraintSet constraints = crossingLines(mesh, 300, 8);
    std::size_t calls = 0;
    double lastFraction = -1.0;
    const ConstrainedTin tin =
        insertConstraints(mesh, constraints, [&](double fraction, std::string_view message) {
            ++calls;
            EXPECT_EQ(message, "inserting constraints");
            EXPECT_GE(fraction, lastFraction);
            EXPECT_LE(fraction, 1.0);
            lastFraction = fraction;
            return true;
        });
    test::expectConstrainedDelaunay(tin, mesh, constraints);
    ASSERT_GT(tin.intersections, 5000U);
    // Each crossing splits the segment going in: a piece, a step, per crossing at least.
    EXPECT_GE(calls, tin.intersections / 64);

    const std::size_t stopAt = calls / 4;
    std::size_t callsMade = 0;
    double stoppedAt = 1.0;
    EXPECT_THROW((void)insertConstraints(mesh, constraints,
                                         [&](double fraction, std::string_view) {
                                             ++callsMade;
                                             stoppedAt = fraction;
                                             return callsMade < stopAt;
                                         }),
                 Cancelled);
    EXPECT_EQ(callsMade, stopAt);
    EXPECT_LT(stoppedAt, 0.9); // most of the lines were still to go in
}

// With zones the calling thread watches the callback while the zones' threads insert, and what
// the zones leave goes in on it, polled as above: a cancel is honoured there too.
TEST(InsertConstraints, ACancelDuringZonedInsertion_ThrowsCancelledAtTheCallThatSaidStop) {
    const TinMesh mesh = delaunayOf(test::generatePoints(Distribution::Uniform, 3000, 32));
    std::vector<std::vector<Point3>> lines = crossingLines(mesh, 300, 9).polylines;
    ConstraintSet constraints = test::locatedPolylines(mesh, lines);
    constraints.zones = 4;
    constraints.threads = 4;
    std::size_t calls = 0;
    EXPECT_THROW((void)insertConstraints(mesh, constraints,
                                         [&](double, std::string_view) {
                                             ++calls;
                                             return false;
                                         }),
                 Cancelled);
    EXPECT_EQ(calls, 1U);
}

TEST(InsertConstraints, SegmentAlongTheHull) {
    const TinMesh mesh = delaunayOf(grid(5));
    ConstraintSet constraints;
    constraints.segments = {{vertexAt(mesh, 0, 0), vertexAt(mesh, 4, 0)},
                            {vertexAt(mesh, 4, 4), vertexAt(mesh, 4, 0)}};
    const ConstrainedTin tin = constrainAndCheck(mesh, constraints);
    EXPECT_EQ(tin.chains[0].size(), 5U);
}

TEST(InsertConstraints, DuplicateInputPoints) {
    const std::vector<Point3> points =
        test::withDuplicates(test::generatePoints(Distribution::Cluster, 1500, 12), 300, 4);
    const TinMesh mesh = delaunayOf(points);
    ConstraintSet constraints;
    constraints.segments = test::randomSegments(mesh.vertexCount(), 100, 13);
    for (std::size_t k = 0; k < 20; ++k) { // polyline points at existing (duplicated) inputs
        const Point3& p = points[points.size() - 1 - k];
        constraints.polylines.push_back({p, {0.5, 0.5, 0}});
    }
    constrainAndCheck(mesh, constraints);
}

TEST(InsertConstraints, PolylinePointOnAHullEdgeSplitsIt) {
    const TinMesh mesh = delaunayOf(grid(4));
    ConstraintSet constraints;
    constraints.polylines = {{{1.5, 0, 7}, {1.5, 2, 7}}};
    const ConstrainedTin tin = constrainAndCheck(mesh, constraints);
    EXPECT_EQ(tin.addedPoints, 2U);
    EXPECT_EQ(tin.chains[0].size(), 2U); // no grid vertex lies on x = 1.5
    std::size_t hullEdges = 0;
    for (const std::int32_t neighbour : tin.mesh.neighbours)
        hullEdges += neighbour == kNoNeighbour ? 1U : 0U;
    EXPECT_EQ(hullEdges, 13U); // the grid's 12 and one more for the split
}

// The second polyline's first point lies exactly on an edge the first made constrained: the
// edge is split and the first chain passes through the new vertex.
TEST(InsertConstraints, PolylinePointOnAConstrainedEdgeSplitsIt) {
    const TinMesh mesh = delaunayOf(grid(4));
    ConstraintSet constraints;
    constraints.polylines = {{{0.5, 0.5, 0}, {2.5, 2.5, 0}}, {{1.5, 1.5, 0}, {2.5, 0.5, 0}}};
    const ConstrainedTin tin = constrainAndCheck(mesh, constraints);
    const std::vector<std::uint32_t>& first = tin.chains[0];
    const std::uint32_t split = tin.chains[1].front();
    EXPECT_EQ(tin.mesh.vertices[split], (Point3{1.5, 1.5, 0}));
    EXPECT_NE(std::find(first.begin(), first.end(), split), first.end());
    EXPECT_EQ(first.size(), 5U); // (0.5, 0.5), (1, 1), (1.5, 1.5), (2, 2), (2.5, 2.5)
}

TEST(InsertConstraints, Throws_WhenAPolylinePointIsOutsideTheHull) {
    const TinMesh mesh = delaunayOf(grid(4));
    ConstraintSet constraints;
    constraints.polylines = {{{1, 1, 0}, {2, 2, 0}}, {{1, 1, 0}, {2.5, 2.5, 0}, {3.25, 1, 0}}};
    try {
        (void)insertConstraints(mesh, constraints);
        FAIL() << "no exception";
    } catch (const InvalidInputError& error) {
        EXPECT_NE(std::string(error.what()).find("polyline 1, point 2"), std::string::npos)
            << error.what();
    }
}

TEST(InsertConstraints, Throws_WhenAVertexIndexIsOutOfRange) {
    const TinMesh mesh = delaunayOf(grid(4));
    ConstraintSet constraints;
    constraints.segments = {{0, 1}, {2, 16}};
    EXPECT_THROW((void)insertConstraints(mesh, constraints), InvalidInputError);
}

TEST(InsertConstraints, Throws_WhenAPointIsNotFinite) {
    const TinMesh mesh = delaunayOf(grid(4));
    ConstraintSet constraints;
    constraints.polylines = {{{1, 1, 0}, {2, std::nan(""), 0}}};
    EXPECT_THROW((void)insertConstraints(mesh, constraints), InvalidInputError);
}

// The triangles of `mesh` as sorted corner triples, sorted: the triangulation whatever the
// numbering of its triangles.
std::vector<std::array<std::uint32_t, 3>> triangleSet(const TinMesh& mesh) {
    std::vector<std::array<std::uint32_t, 3>> triangles;
    for (std::size_t t = 0; t < mesh.triangleCount(); ++t) {
        std::array<std::uint32_t, 3> corners{mesh.triangles[3 * t], mesh.triangles[3 * t + 1],
                                             mesh.triangles[3 * t + 2]};
        std::sort(corners.begin(), corners.end());
        triangles.push_back(corners);
    }
    std::sort(triangles.begin(), triangles.end());
    return triangles;
}

// The same vertices, in the same order, the same chains and the same triangles (numbered
// alike or not), with crossings among the constraints.
void expectSameTin(const ConstrainedTin& a, const ConstrainedTin& b) {
    EXPECT_GT(a.intersections, 10U);
    EXPECT_EQ(a.mesh.vertices, b.mesh.vertices);
    EXPECT_EQ(a.chains, b.chains);
    EXPECT_EQ(triangleSet(a.mesh), triangleSet(b.mesh));
}

TEST(InsertConstraints, PolylineTrianglesGiveTheSameTin_AsTheSearchWithout) {
    const TinMesh mesh = delaunayOf(test::generatePoints(Distribution::Uniform, 3000, 21));
    ConstraintSet located = test::walksWithTriangles(mesh, 40, 30, 5);
    ASSERT_GT(located.polylines.size(), 30U);
    ConstraintSet searched = located;
    searched.polylineTriangles.clear();
    // Points in general position: one constrained Delaunay triangulation, its vertices made in
    // the same order.
    expectSameTin(constrainAndCheck(mesh, located), constrainAndCheck(mesh, searched));
}

// clipToSurface leaves points inside the hull unlocated (kFromPreviousPoint): found from the
// previous point's vertex, in zones and on one thread, they give the TIN that every point's own
// triangle gives; a polyline's first point given as kFromPreviousPoint is searched for
// anywhere.
TEST(InsertConstraints, PointsFromThePreviousPoint_GiveTheSameTin_AsEveryPointLocated) {
    const TinMesh mesh = delaunayOf(test::generatePoints(Distribution::Uniform, 3000, 22));
    ConstraintSet fromPrevious = test::walksWithTriangles(mesh, 40, 30, 6);
    ConstraintSet located = fromPrevious;
    TinLocator locator(mesh);
    std::size_t unlocated = 0;
    for (std::size_t k = 0; k < located.polylines.size(); ++k)
        for (std::size_t j = 0; j < located.polylines[k].size(); ++j)
            if (std::uint32_t& t = located.polylineTriangles[k][j]; t == kFromPreviousPoint) {
                const Point3& p = located.polylines[k][j];
                t = locator.locate({p.x, p.y}).value();
                ++unlocated;
            }
    ASSERT_GT(unlocated, 500U);
    for (const unsigned zones : {2U, 1U}) {
        SCOPED_TRACE(zones);
        if (zones == 1)
            for (std::size_t k = 0; k < fromPrevious.polylines.size(); k += 5)
                fromPrevious.polylineTriangles[k][0] = kFromPreviousPoint;
        fromPrevious.zones = located.zones = zones;
        fromPrevious.threads = located.threads = 2;
        expectSameTin(constrainAndCheck(mesh, fromPrevious), constrainAndCheck(mesh, located));
    }
}

// Polylines on a grid's vertices and along its lines, with their triangles: the segments run
// along edges through vertices that nothing before touched (the vertex-to-triangle map is
// completed only on demand).
TEST(InsertConstraints, GridLinePolylinesWithTriangles_AlongEdgesThroughUntouchedVertices) {
    const int n = 31;
    const TinMesh mesh = delaunayOf(grid(n));
    std::vector<std::vector<Point3>> lines;
    for (int k = 1; k < n - 1; k += 4) {
        lines.push_back({{0, double(k), 0}, {double(n - 1), double(k), 0}});
        lines.push_back({{double(k), 0.5, 0}, {double(k), 20, 0}, {double(n - 1), 29.5, 0}});
    }
    const ConstraintSet constraints = test::locatedPolylines(mesh, lines);
    const ConstrainedTin tin = constrainAndCheck(mesh, constraints);
    EXPECT_EQ(tin.chains[0].size(), std::size_t(n)); // every vertex of the row
    EXPECT_GT(tin.intersections, 0U);
    ConstraintSet searched = constraints;
    searched.polylineTriangles.clear();
    EXPECT_EQ(constrainAndCheck(mesh, searched).chains, tin.chains);
}

TEST(InsertConstraints, IsConstrainedDelaunay_WhenPolylineTrianglesAreFarFromTheirPoints) {
    const TinMesh mesh = delaunayOf(test::generatePoints(Distribution::Grid, 3000, 3));
    ConstraintSet constraints = test::walksWithTriangles(mesh, 20, 30, 8);
    for (std::vector<std::uint32_t>& triangles : constraints.polylineTriangles)
        std::fill(triangles.begin(), triangles.end(), 0U);
    constrainAndCheck(mesh, constraints);
}

TEST(InsertConstraints, Throws_WhenPolylineTrianglesDoNotMatchThePolylines) {
    const TinMesh mesh = delaunayOf(grid(4));
    ConstraintSet constraints;
    constraints.polylines = {{{1, 1, 0}, {2, 2, 0}}};
    constraints.polylineTriangles = {{0}};
    EXPECT_THROW((void)insertConstraints(mesh, constraints), InvalidInputError);
    constraints.polylineTriangles = {{0, 0}, {0, 0}};
    EXPECT_THROW((void)insertConstraints(mesh, constraints), InvalidInputError);
    constraints.polylineTriangles = {{0, static_cast<std::uint32_t>(mesh.triangleCount())}};
    EXPECT_THROW((void)insertConstraints(mesh, constraints), InvalidInputError);
    constraints.polylineTriangles = {{0, static_cast<std::uint32_t>(mesh.triangleCount() - 1)}};
    EXPECT_NO_THROW((void)insertConstraints(mesh, constraints));
}

TEST(InsertConstraints, CopiesNoArray_WhenTheMeshHasRoomForTheNewVertices) {
    const std::vector<Point3> points = test::generatePoints(Distribution::Uniform, 2000, 4);
    TriangulationOptions roomy;
    roomy.spareVertices = 500;
    TinMesh mesh = triangulate(points, roomy).mesh;
    const TinMesh plain = delaunayOf(points);
    EXPECT_EQ(mesh.triangles, plain.triangles); // the room changes nothing else
    EXPECT_GE(mesh.vertices.capacity(), mesh.vertexCount() + 500);
    EXPECT_GE(mesh.triangles.capacity(), 3 * (mesh.triangleCount() + 2 * 500));
    // Crossing polylines zigzagging over the middle: new vertices and crossings.
    ConstraintSet constraints;
    for (int k = 0; k < 10; ++k) {
        std::vector<Point3> line;
        for (int j = 0; j < 10; ++j) {
            const double along = 0.2 + 0.06 * j;
            const double across = 0.25 + 0.05 * k + (j % 2 == 0 ? 0.0 : 0.03);
            line.push_back(k % 2 == 0 ? Point3{along, across, 0.0} : Point3{across, along, 0.0});
        }
        constraints.polylines.push_back(line);
    }
    const Point3* vertices = mesh.vertices.data();
    const std::uint32_t* triangles = mesh.triangles.data();
    const std::int32_t* neighbours = mesh.neighbours.data();
    const ConstrainedTin tin = insertConstraints(std::move(mesh), constraints);
    EXPECT_GT(tin.addedPoints, 90U);
    EXPECT_GT(tin.intersections, 0U);
    EXPECT_LE(tin.addedPoints + tin.intersections, 500U);
    EXPECT_EQ(tin.mesh.vertices.data(), vertices);
    EXPECT_EQ(tin.mesh.triangles.data(), triangles);
    EXPECT_EQ(tin.mesh.neighbours.data(), neighbours);
    test::expectConstrainedDelaunay(tin, plain, constraints);
}

TEST(InsertConstraints, NoConstraintsLeavesTheMesh) {
    const TinMesh mesh = delaunayOf(test::generatePoints(Distribution::Gauss, 300, 2));
    const ConstrainedTin tin = constrainAndCheck(mesh, {});
    EXPECT_EQ(tin.mesh.triangles, mesh.triangles);
    EXPECT_EQ(tin.mesh.neighbours, mesh.neighbours);
}

} // namespace
} // namespace terratin

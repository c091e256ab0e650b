// The strip method's core driven directly, with strips allowed from a few points per strip so
// that moderate inputs (fast under ThreadSanitizer) run in strips in every round but the first.

#include "insertion_order.hpp"
#include "strip_insertion.hpp"

#include "mesh_invariants.hpp"
#include "point_distributions.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>
#include <string>
#include <tuple>

namespace terratin {
namespace {

using detail::StripTriangulator;
using test::Distribution;

constexpr std::size_t kPoints = 20000;
constexpr std::size_t kSmallStripMinimum = 32;

// The distinct points of `input` (the library's preparePoints does this before insertion).
std::vector<Point3> distinct(std::vector<Point3> input) {
    std::sort(input.begin(), input.end(),
              [](const Point3& a, const Point3& b) { return a.x != b.x ? a.x < b.x : a.y < b.y; });
    input.erase(
        std::unique(input.begin(), input.end(),
                    [](const Point3& a, const Point3& b) { return a.x == b.x && a.y == b.y; }),
        input.end());
    return input;
}

struct StripRun {
    TinMesh mesh;
    std::size_t deferred = 0;
};

StripRun triangulateInStrips(const std::vector<Point3>& points, unsigned strips) {
    std::vector<Point2> planar;
    for (const Point3& p : points)
        planar.push_back({p.x, p.y});
    std::vector<std::size_t> roundStarts;
    const auto order = detail::brioInsertionOrder(planar, 0xFFFFFFFFU, 7, &roundStarts);
    StripTriangulator triangulator(planar, strips, kSmallStripMinimum);
    triangulator.insertAll(order, roundStarts, {});
    StripRun run;
    triangulator.extract(run.mesh.triangles, run.mesh.neighbours, strips);
    run.mesh.vertices.assign(points.begin(), points.end());
    run.mesh.sourceIndex.resize(points.size());
    std::iota(run.mesh.sourceIndex.begin(), run.mesh.sourceIndex.end(), 0U);
    run.deferred = triangulator.deferredPoints();
    return run;
}

class StripInsertion : public ::testing::TestWithParam<std::tuple<unsigned, Distribution>> {};

TEST_P(StripInsertion, IsExactlyDelaunay_AndDefersOnlyPointsNearStripBoundaries) {
    const auto [strips, distribution] = GetParam();
    const std::vector<Point3> points = distinct(test::generatePoints(distribution, kPoints, 3));
    const StripRun run = triangulateInStrips(points, strips);
    test::expectExactDelaunayOf(run.mesh, points);
    // Every strip boundary defers some points, and phase 1 inserts the others: most of them
    // where triangles are small and round, more with more (narrower) strips. On the arc
    // every triangle is long and thin, and a cluster leaves few points to most strips, so
    // more of them meet a boundary.
    EXPECT_GT(run.deferred, 0U);
    const bool roundTriangles = distribution == Distribution::Uniform ||
                                distribution == Distribution::Gauss ||
                                distribution == Distribution::Grid;
    EXPECT_LT(run.deferred, roundTriangles ? points.size() * strips / 16 : points.size());
}

INSTANTIATE_TEST_SUITE_P(
    StripsDistributions, StripInsertion,
    ::testing::Combine(::testing::Values(2U, 3U, 4U, 8U),
                       ::testing::Values(Distribution::Uniform, Distribution::Gauss,
                                         Distribution::Cluster, Distribution::Grid,
                                         Distribution::Arc)),
    [](const auto& paramInfo) {
        return std::to_string(std::get<0>(paramInfo.param)) + "strips_" +
               test::toString(std::get<1>(paramInfo.param));
    });

// A point refused by its strip is retried by a thread of merged strips, so only points by the
// middle boundary reach the single thread: with 8 strips about as many as with 2, not 7
// boundaries' worth.
TEST(StripInsertion, MergedStripsLeaveOneBoundaryToTheSingleThread) {
    const std::vector<Point3> points =
        distinct(test::generatePoints(Distribution::Uniform, kPoints, 11));
    const std::size_t twoStrips = triangulateInStrips(points, 2).deferred;
    const StripRun eight = triangulateInStrips(points, 8);
    test::expectExactDelaunayOf(eight.mesh, points);
    EXPECT_GT(twoStrips, 0U);
    EXPECT_LT(eight.deferred, 2 * twoStrips) << twoStrips;
}

TEST(StripInsertion, DependsOnlyOnTheStripCount_NotOnThreadTiming) {
    // Grid points are cocircular in every cell: the diagonals follow the insertion order, so
    // any dependence on which thread ran first would show as a different mesh.
    const std::vector<Point3> points =
        distinct(test::generatePoints(Distribution::Grid, kPoints, 5));
    const StripRun first = triangulateInStrips(points, 3);
    for (int repeat = 0; repeat < 3; ++repeat) {
        const StripRun again = triangulateInStrips(points, 3);
        EXPECT_EQ(again.mesh.triangles, first.mesh.triangles);
        EXPECT_EQ(again.deferred, first.deferred);
    }
}

TEST(StripInsertion, IsExactlyDelaunay_ForLargeOffsetGridsAndCocircularRings) {
    for (const std::vector<Point3>& points :
         {distinct(
              test::offset(test::generatePoints(Distribution::Grid, kPoints, 3), 6.0e5, 5.2e6)),
          distinct(test::cocircularRings(1.0)), distinct(test::collinearPlusOne(3000))}) {
        test::expectExactDelaunayOf(triangulateInStrips(points, 4).mesh, points);
    }
}

} // namespace
} // namespace terratin

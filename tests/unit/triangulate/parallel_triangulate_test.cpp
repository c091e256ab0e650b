// Every parallel method, at several thread counts, on every input kind: the result must be
// exactly Delaunay and the very triangles of the sequential result (cocircular ties are broken
// the same way whatever the order of insertion).

#include "terratin/triangulate/triangulate.hpp"

#include "mesh_invariants.hpp"
#include "point_distributions.hpp"
#include "terratin/error.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <span>
#include <string>
#include <tuple>

namespace terratin {
namespace {

using test::Distribution;

// Sizes kept moderate: the suite also runs under ThreadSanitizer, which slows threads ~10x.
constexpr std::size_t kPoints = 6000;

TriangulationOptions parallelOptions(TriangulationMethod method, unsigned threads,
                                     PointLocation locate = PointLocation::Dag) {
    TriangulationOptions options;
    options.method = method;
    options.threads = threads;
    options.locate = locate;
    options.collectDiagnostics = true;
    return options;
}

const char* toString(PointLocation locate) {
    return locate == PointLocation::Dag ? "dag" : "walk";
}

void expectTheSequentialTin(const TinMesh& parallel, std::span<const Point3> points) {
    TriangulationOptions sequential;
    sequential.method = TriangulationMethod::Sequential;
    test::expectSameTriangles(parallel, triangulate(points, sequential).mesh);
}

class ParallelMethod : public ::testing::TestWithParam<
                           std::tuple<TriangulationMethod, PointLocation, unsigned, Distribution>> {
};

TEST_P(ParallelMethod, IsExactlyDelaunayAndTheSequentialTin_ForPaperDistributions) {
    const auto [method, locate, threads, distribution] = GetParam();
    const std::vector<Point3> points = test::generatePoints(distribution, kPoints, 5);
    const TriangulationResult result =
        triangulate(points, parallelOptions(method, threads, locate));
    EXPECT_EQ(result.method, method);
    test::expectExactDelaunayOf(result.mesh, points);
    expectTheSequentialTin(result.mesh, points);
}

INSTANTIATE_TEST_SUITE_P(
    MethodsThreadsDistributions, ParallelMethod,
    ::testing::Combine(
        ::testing::Values(TriangulationMethod::Batch, TriangulationMethod::Circumcircle),
        ::testing::Values(PointLocation::Dag, PointLocation::Walk),
        ::testing::Values(1U, 2U, 3U, 4U, 8U),
        ::testing::Values(Distribution::Uniform, Distribution::Gauss, Distribution::Cluster,
                          Distribution::Grid, Distribution::Arc)),
    [](const auto& paramInfo) {
        return std::string(toString(std::get<0>(paramInfo.param))) + "_" +
               toString(std::get<1>(paramInfo.param)) + "_" +
               std::to_string(std::get<2>(paramInfo.param)) + "threads_" +
               test::toString(std::get<3>(paramInfo.param));
    });

// The strip method always walks: one location is enough.
INSTANTIATE_TEST_SUITE_P(
    StripsThreadsDistributions, ParallelMethod,
    ::testing::Combine(::testing::Values(TriangulationMethod::Strips),
                       ::testing::Values(PointLocation::Walk),
                       ::testing::Values(1U, 2U, 3U, 4U, 8U),
                       ::testing::Values(Distribution::Uniform, Distribution::Gauss,
                                         Distribution::Cluster, Distribution::Grid,
                                         Distribution::Arc)),
    [](const auto& paramInfo) {
        return std::to_string(std::get<2>(paramInfo.param)) + "threads_" +
               test::toString(std::get<3>(paramInfo.param));
    });

class ParallelDegenerate
    : public ::testing::TestWithParam<std::tuple<TriangulationMethod, PointLocation, unsigned>> {
protected:
    [[nodiscard]] TriangulationOptions options() const {
        const auto [method, locate, threads] = GetParam();
        return parallelOptions(method, threads, locate);
    }
};

TEST_P(ParallelDegenerate, IsExactlyDelaunay_ForDuplicates) {
    const std::vector<Point3> points = test::withDuplicates(
        test::generatePoints(Distribution::Uniform, kPoints, 8), kPoints / 4, 9);
    const TriangulationResult result = triangulate(points, options());
    EXPECT_EQ(result.duplicatePoints, kPoints / 4);
    test::expectExactDelaunayOf(result.mesh, points);
    expectTheSequentialTin(result.mesh, points);
}

TEST_P(ParallelDegenerate, IsExactlyDelaunay_ForCollinearPlusOne) {
    const std::vector<Point3> points = test::collinearPlusOne(2000);
    test::expectExactDelaunayOf(triangulate(points, options()).mesh, points);
}

TEST_P(ParallelDegenerate, IsExactlyDelaunay_ForCocircularRings) {
    const std::vector<Point3> points = test::cocircularRings(1.0);
    const TinMesh mesh = triangulate(points, options()).mesh;
    test::expectExactDelaunayOf(mesh, points);
    expectTheSequentialTin(mesh, points);
}

TEST_P(ParallelDegenerate, IsExactlyDelaunay_ForLargeOffsets) {
    const std::vector<Point3> points =
        test::offset(test::generatePoints(Distribution::Grid, kPoints, 3), 6.0e5, 5.2e6);
    const TinMesh mesh = triangulate(points, options()).mesh;
    test::expectExactDelaunayOf(mesh, points);
    expectTheSequentialTin(mesh, points);
}

TEST_P(ParallelDegenerate, Terminates_WhenFewPointsMeetManyThreads) {
    for (std::size_t count : {3U, 4U, 5U, 10U, 40U}) {
        const std::vector<Point3> points = test::generatePoints(Distribution::Arc, count, count);
        test::expectExactDelaunayOf(triangulate(points, options()).mesh, points);
    }
}

INSTANTIATE_TEST_SUITE_P(MethodsThreads, ParallelDegenerate,
                         ::testing::Combine(::testing::Values(TriangulationMethod::Batch,
                                                              TriangulationMethod::Circumcircle),
                                            ::testing::Values(PointLocation::Dag,
                                                              PointLocation::Walk),
                                            ::testing::Values(1U, 2U, 3U, 4U, 8U)),
                         [](const auto& paramInfo) {
                             return std::string(toString(std::get<0>(paramInfo.param))) + "_" +
                                    toString(std::get<1>(paramInfo.param)) + "_" +
                                    std::to_string(std::get<2>(paramInfo.param)) + "threads";
                         });

INSTANTIATE_TEST_SUITE_P(StripsThreads, ParallelDegenerate,
                         ::testing::Combine(::testing::Values(TriangulationMethod::Strips),
                                            ::testing::Values(PointLocation::Walk),
                                            ::testing::Values(1U, 2U, 3U, 4U, 8U)),
                         [](const auto& paramInfo) {
                             return std::to_string(std::get<2>(paramInfo.param)) + "threads";
                         });

TEST(StripMethod, RunsItsStripsInParallel_OnALargeInput) {
    // Large enough for the library's own threshold: rounds of over 4096 points per strip.
    // On clusters a strip's points jump from one cluster to the next across other strips'
    // triangles: the checkpoints must keep those jumps from deferring whole clusters.
    for (const Distribution distribution : {Distribution::Uniform, Distribution::Cluster}) {
        const std::vector<Point3> points = test::generatePoints(distribution, 40000, 12);
        const TriangulationResult result =
            triangulate(points, parallelOptions(TriangulationMethod::Strips, 2));
        EXPECT_EQ(result.threads, 2U);
        ASSERT_TRUE(result.diagnostics);
        EXPECT_GT(result.diagnostics->deferredPoints, 0U);
        EXPECT_LT(result.diagnostics->deferredPoints, points.size() / 20)
            << test::toString(distribution);
        test::expectExactDelaunayOf(result.mesh, points);
    }
}

TEST(StripMethod, IsWhatAutoChooses_WithTheBrioOrder) {
    const std::vector<Point3> points = test::generatePoints(Distribution::Gauss, 500, 2);
    for (const unsigned threads : {1U, 2U}) {
        const TriangulationResult result =
            triangulate(points, parallelOptions(TriangulationMethod::Auto, threads));
        EXPECT_EQ(result.method, TriangulationMethod::Strips);
        ASSERT_TRUE(result.diagnostics);
        EXPECT_EQ(result.diagnostics->historyNodes, 0U);
        test::expectExactDelaunayOf(result.mesh, points);
    }
    // A random order makes walks long: auto then descends the DAG.
    TriangulationOptions random = parallelOptions(TriangulationMethod::Auto, 2);
    random.order = InsertionOrder::Random;
    const TriangulationResult result = triangulate(points, random);
    EXPECT_EQ(result.method, TriangulationMethod::Sequential);
    ASSERT_TRUE(result.diagnostics);
    EXPECT_GT(result.diagnostics->historyNodes, 0U);
}

TEST(StripMethod, ThrowsCancelled) {
    const std::vector<Point3> points = test::generatePoints(Distribution::Uniform, 200000, 4);
    std::size_t calls = 0;
    EXPECT_THROW(triangulate(points, parallelOptions(TriangulationMethod::Strips, 2),
                             [&calls](double, std::string_view) { return ++calls < 2; }),
                 Cancelled);
}

TEST(CircumcircleMethod, IsExactlyDelaunay_WhenThreadsCrowdOneCircle) {
    // Points on one circle: every triangle's circumcircle is (nearly) that circle, so every
    // thread's point conflicts with every other's and the waits and overrides are exercised.
    std::size_t overrides = 0;
    for (const PointLocation locate : {PointLocation::Dag, PointLocation::Walk}) {
        for (const unsigned threads : {2U, 4U, 8U}) {
            std::vector<Point3> points = test::cocircularRings(1.0);
            const std::vector<Point3> arc = test::generatePoints(Distribution::Arc, 3000, threads);
            points.insert(points.end(), arc.begin(), arc.end());
            const TriangulationResult result = triangulate(
                points, parallelOptions(TriangulationMethod::Circumcircle, threads, locate));
            EXPECT_EQ(result.threads, threads);
            test::expectExactDelaunayOf(result.mesh, points);
            // Every override is followed by a repair; several may share one.
            ASSERT_TRUE(result.diagnostics);
            const MethodDiagnostics& counted = *result.diagnostics;
            EXPECT_EQ(counted.repairs > 0, counted.overrides > 0);
            EXPECT_LE(counted.repairs, counted.overrides);
            overrides += counted.overrides;
        }
    }
    EXPECT_GT(overrides, 0U) << "the input no longer provokes overrides";
}

TEST(CircumcircleMethod, ThrowsCancelled_AndStopsEveryThread) {
    const std::vector<Point3> points = test::generatePoints(Distribution::Uniform, 200000, 4);
    std::size_t calls = 0;
    EXPECT_THROW(triangulate(points, parallelOptions(TriangulationMethod::Circumcircle, 4),
                             [&calls](double, std::string_view) { return ++calls < 2; }),
                 Cancelled);
}

TEST(CircumcircleMethod, ReportsProgressInStepsThroughTheLastRound) {
    // The last BRIO round holds half the points: progress must not jump over it.
    const std::vector<Point3> points = test::generatePoints(Distribution::Uniform, 300000, 6);
    std::vector<double> fractions;
    triangulate(points, parallelOptions(TriangulationMethod::Circumcircle, 2),
                [&fractions](double fraction, std::string_view) {
                    fractions.push_back(fraction);
                    return true;
                });
    EXPECT_TRUE(std::is_sorted(fractions.begin(), fractions.end()));
    const auto inLastHalf = std::count_if(fractions.begin(), fractions.end(),
                                          [](double f) { return f > 0.5 && f < 1.0; });
    EXPECT_GE(inLastHalf, 2);
}

TEST(BatchMethod, IsExactlyDelaunay_WhenSearchersHelpOnAFullQueue) {
    const std::vector<Point3> points = test::generatePoints(Distribution::Uniform, 20000, 4);
    TriangulationOptions options = parallelOptions(TriangulationMethod::Batch, 2);
    options.searchers = 4;
    options.queueLength = 4; // tiny: the queue is full almost always
    options.searchersHelpWhenQueueFull = true;
    const TriangulationResult result = triangulate(points, options);
    ASSERT_TRUE(result.diagnostics);
    EXPECT_EQ(result.diagnostics->searchers, 4U);
    // Only locations that really advanced count: at most one per point and queue pass, not
    // the endless re-queueing of already complete locations.
    EXPECT_LE(result.diagnostics->helpedLocations, 20U * points.size());
    test::expectExactDelaunayOf(result.mesh, points);
}

TEST(BatchMethod, UsesRequestedSearchersAndQueue) {
    const std::vector<Point3> points = test::generatePoints(Distribution::Gauss, 5000, 4);
    TriangulationOptions options = parallelOptions(TriangulationMethod::Batch, 2);
    options.searchers = 6;
    options.queueLength = 3;
    const TriangulationResult result = triangulate(points, options);
    ASSERT_TRUE(result.diagnostics);
    EXPECT_EQ(result.diagnostics->searchers, 6U);
    EXPECT_EQ(result.threads, 7U);
    test::expectExactDelaunayOf(result.mesh, points);
}

TEST(BatchMethod, ThrowsCancelled_AndStopsEveryThread) {
    const std::vector<Point3> points = test::generatePoints(Distribution::Uniform, 200000, 4);
    std::size_t calls = 0;
    EXPECT_THROW(triangulate(points, parallelOptions(TriangulationMethod::Batch, 4),
                             [&calls](double, std::string_view) { return ++calls < 2; }),
                 Cancelled);
}

} // namespace
} // namespace terratin

#include "terratin/triangulate/triangulate.hpp"

#include "mesh_invariants.hpp"
#include "point_distributions.hpp"
#include "terratin/error.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <tuple>

namespace terratin {
namespace {

using test::Distribution;

class TriangulateDistribution
    : public ::testing::TestWithParam<std::tuple<Distribution, std::size_t>> {};

TEST_P(TriangulateDistribution, IsExactlyDelaunay_ForPaperDistributions) {
    const auto [distribution, count] = GetParam();
    const std::vector<Point3> points = test::generatePoints(distribution, count, 42);
    const TriangulationResult result = triangulate(points);
    test::expectExactDelaunayOf(result.mesh, points);
}

TEST_P(TriangulateDistribution, IsExactlyDelaunay_WhenOffsetByAMillion) {
    const auto [distribution, count] = GetParam();
    const std::vector<Point3> points =
        test::offset(test::generatePoints(distribution, count, 7), 1.0e6, 5.0e6);
    const TriangulationResult result = triangulate(points);
    test::expectExactDelaunayOf(result.mesh, points);
}

TEST_P(TriangulateDistribution, IsExactlyDelaunay_WithPlainRandomOrder) {
    const auto [distribution, count] = GetParam();
    const std::vector<Point3> points = test::generatePoints(distribution, count, 11);
    TriangulationOptions options;
    options.order = InsertionOrder::Random;
    test::expectExactDelaunayOf(triangulate(points, options).mesh, points);
}

TEST_P(TriangulateDistribution, IsExactlyDelaunay_WithWalkLocation) {
    const auto [distribution, count] = GetParam();
    const std::vector<Point3> points = test::generatePoints(distribution, count, 13);
    TriangulationOptions options;
    options.method = TriangulationMethod::Sequential;
    options.locate = PointLocation::Walk;
    const TriangulationResult result = triangulate(points, options);
    EXPECT_EQ(result.method, TriangulationMethod::Sequential);
    test::expectExactDelaunayOf(result.mesh, points);
}

INSTANTIATE_TEST_SUITE_P(
    PaperDistributions, TriangulateDistribution,
    ::testing::Combine(::testing::Values(Distribution::Uniform, Distribution::Gauss,
                                         Distribution::Cluster, Distribution::Grid,
                                         Distribution::Arc),
                       ::testing::Values(std::size_t{10}, std::size_t{1000}, std::size_t{30000})),
    [](const auto& paramInfo) {
        return test::toString(std::get<0>(paramInfo.param)) + "_" +
               std::to_string(std::get<1>(paramInfo.param));
    });

TEST(Triangulate, MergesDuplicates_KeepingFirstElevationByDefault) {
    const std::vector<Point3> base = test::generatePoints(Distribution::Uniform, 2000, 3);
    const std::vector<Point3> points = test::withDuplicates(base, 500, 4);
    const TriangulationResult result = triangulate(points);
    EXPECT_EQ(result.inputPoints, points.size());
    EXPECT_EQ(result.duplicatePoints, 500U);
    EXPECT_EQ(result.mesh.vertexCount(), base.size());
    test::expectExactDelaunayOf(result.mesh, points);
    for (std::size_t v = 0; v < result.mesh.vertexCount(); ++v) {
        EXPECT_LT(result.mesh.sourceIndex[v], base.size()) << "the first occurrence survives";
        EXPECT_EQ(result.mesh.vertices[v].z, base[result.mesh.sourceIndex[v]].z);
    }
}

TEST(Triangulate, DuplicatePolicy_ChoosesSurvivingElevation) {
    const std::vector<Point3> points{{0, 0, 5}, {1, 0, 1}, {0, 1, 2}, {0, 0, 9}, {0, 0, 1}};
    const auto zAtOrigin = [&](DuplicateZPolicy policy) {
        TriangulationOptions options;
        options.duplicateZ = policy;
        const TinMesh mesh = triangulate(points, options).mesh;
        for (const Point3& v : mesh.vertices)
            if (v.x == 0 && v.y == 0)
                return v.z;
        return std::nan("");
    };
    EXPECT_EQ(zAtOrigin(DuplicateZPolicy::First), 5.0);
    EXPECT_EQ(zAtOrigin(DuplicateZPolicy::Last), 1.0);
    EXPECT_EQ(zAtOrigin(DuplicateZPolicy::Min), 1.0);
    EXPECT_EQ(zAtOrigin(DuplicateZPolicy::Max), 9.0);
    EXPECT_EQ(zAtOrigin(DuplicateZPolicy::Mean), 5.0);
}

TEST(Triangulate, IsExactlyDelaunay_ForCollinearPointsPlusOne) {
    const std::vector<Point3> points = test::collinearPlusOne(500);
    const TriangulationResult result = triangulate(points);
    EXPECT_EQ(result.mesh.triangleCount(), 499U);
    test::expectExactDelaunayOf(result.mesh, points);
}

TEST(Triangulate, IsExactlyDelaunay_ForCocircularRings) {
    for (const double scale : {1.0, 1.0 / 1024.0}) {
        const std::vector<Point3> points = test::cocircularRings(scale);
        const TriangulationResult result = triangulate(points);
        test::expectExactDelaunayOf(result.mesh, points);
    }
}

TEST(Triangulate, IsExactlyDelaunay_ForCocircularRingsFarFromOrigin) {
    const std::vector<Point3> points = test::offset(test::cocircularRings(1.0), 4.0e6, 2.0e6);
    test::expectExactDelaunayOf(triangulate(points).mesh, points);
}

TEST(Triangulate, KeepsHullEdges_WhenHullIsNearlyCollinear) {
    // The classic failure of a finite auxiliary triangle: hull vertices that bulge out of a
    // line by far less than the data's extent are lost or get non-Delaunay neighbours.
    std::vector<Point3> points;
    for (int i = 0; i <= 100; ++i) {
        const double x = i;
        points.push_back({x, 1e-9 * x * (100.0 - x), 0.0}); // a barely convex bottom chain
    }
    points.push_back({50.0, 40.0, 0.0});
    points.push_back({20.0, 10.0, 0.0});
    const TriangulationResult result = triangulate(points);
    test::expectExactDelaunayOf(result.mesh, points);
}

TEST(Triangulate, IsExactlyDelaunay_ForGridWithMixedMagnitudes) {
    // Coordinates around 5e6 (UTM northings) with 0.5 m spacing: every cell is cocircular.
    std::vector<Point3> points;
    for (int row = 0; row < 60; ++row)
        for (int col = 0; col < 70; ++col)
            points.push_back({500000.25 + 0.5 * col, 5000000.25 - 0.5 * row, row * 0.1});
    test::expectExactDelaunayOf(triangulate(points).mesh, points);
}

TEST(Triangulate, GivesSameMesh_ForSameSeed) {
    const std::vector<Point3> points = test::generatePoints(Distribution::Uniform, 5000, 9);
    TriangulationOptions options;
    options.seed = 123;
    const TinMesh first = triangulate(points, options).mesh;
    const TinMesh second = triangulate(points, options).mesh;
    EXPECT_EQ(first.triangles, second.triangles);
    EXPECT_EQ(first.neighbours, second.neighbours);
}

TEST(Triangulate, FillsDiagnostics_OnlyWhenAsked) {
    const std::vector<Point3> points = test::generatePoints(Distribution::Uniform, 2000, 3);
    for (const TriangulationMethod method :
         {TriangulationMethod::Sequential, TriangulationMethod::Batch,
          TriangulationMethod::Circumcircle, TriangulationMethod::Strips}) {
        TriangulationOptions options;
        options.method = method;
        options.threads = 2;
        EXPECT_FALSE(triangulate(points, options).diagnostics) << toString(method);
        options.collectDiagnostics = true;
        const TriangulationResult result = triangulate(points, options);
        ASSERT_TRUE(result.diagnostics) << toString(method);
        // The DAG methods keep a history; the strip method none.
        EXPECT_EQ(result.diagnostics->historyNodes > 0, method != TriangulationMethod::Strips)
            << toString(method);
        EXPECT_EQ(result.diagnostics->searchers > 0, method == TriangulationMethod::Batch)
            << toString(method);
    }
}

TEST(Triangulate, IsTheSameExactlyDelaunayTin_ForEverySeedAndOrderOnAGrid) {
    // Every cell of a grid is cocircular: the ties are broken by the points alone, so neither
    // the seed nor the order changes a diagonal.
    const std::vector<Point3> points = test::generatePoints(Distribution::Grid, 400, 1);
    const TinMesh first = triangulate(points, {}).mesh;
    for (const InsertionOrder order : {InsertionOrder::Brio, InsertionOrder::Random})
        for (std::uint64_t seed = 0; seed < 20; ++seed) {
            TriangulationOptions options;
            options.seed = seed;
            options.order = order;
            const TinMesh mesh = triangulate(points, options).mesh;
            EXPECT_EQ(mesh.triangleCount(), 2U * 19U * 19U);
            test::expectExactDelaunayOf(mesh, points);
            test::expectSameTriangles(mesh, first);
        }
}

TEST(Triangulate, WalkLocationIsExact_ForDegenerateInputs) {
    TriangulationOptions options;
    options.locate = PointLocation::Walk;
    for (const std::vector<Point3>& points :
         {test::collinearPlusOne(300), test::cocircularRings(1.0),
          test::withDuplicates(test::generatePoints(Distribution::Grid, 2500, 1), 300, 2),
          test::offset(test::generatePoints(Distribution::Grid, 2500, 1), 5e5, 5e6)})
        test::expectExactDelaunayOf(triangulate(points, options).mesh, points);
}

TEST(Triangulate, TriangulatesThreePoints) {
    const std::vector<Point3> points{{0, 0, 1}, {1, 0, 2}, {0, 1, 3}};
    const TinMesh mesh = triangulate(points).mesh;
    ASSERT_EQ(mesh.triangleCount(), 1U);
    test::expectExactDelaunayOf(mesh, points);
}

TEST(Triangulate, Throws_WhenAllPointsAreCollinear) {
    const std::vector<Point3> points{{0, 0, 0}, {1, 1, 0}, {2, 2, 0}, {3, 3, 0}};
    EXPECT_THROW(triangulate(points), InvalidInputError);
}

TEST(Triangulate, Throws_WhenFewerThanThreeDistinctPoints) {
    const std::vector<Point3> points{{0, 0, 0}, {1, 1, 0}, {0, 0, 5}};
    EXPECT_THROW(triangulate(points), InvalidInputError);
    EXPECT_THROW(triangulate(std::vector<Point3>{}), InvalidInputError);
}

TEST(Triangulate, Throws_WhenACoordinateIsNotFinite) {
    const std::vector<Point3> points{{0, 0, 0}, {1, 0, 0}, {0, 1, NAN}};
    EXPECT_THROW(triangulate(points), InvalidInputError);
}

TEST(Triangulate, ThrowsCancelled_WhenProgressSaysStop) {
    const std::vector<Point3> points = test::generatePoints(Distribution::Uniform, 1000, 2);
    EXPECT_THROW(triangulate(points, {}, [](double, std::string_view) { return false; }),
                 Cancelled);
}

} // namespace
} // namespace terratin

// TinLocator: locating points, the TIN's elevation, and polylines clipped to the hull, with
// every point of a clipped line checked inside by the exact predicate.

#include "terratin/geometry/predicates.hpp"
#include "terratin/triangulate/tin_locator.hpp"
#include "terratin/triangulate/triangulate.hpp"

#include "point_distributions.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

namespace terratin {
namespace {

/// The Delaunay TIN of a 5 x 5 grid at 10 m steps from (1000, 2000), z = 3x + 2y (a plane).
TinMesh planeGrid() {
    std::vector<Point3> points;
    for (int row = 0; row < 5; ++row)
        for (int col = 0; col < 5; ++col) {
            const double x = 1000.0 + 10.0 * col;
            const double y = 2000.0 + 10.0 * row;
            points.push_back({x, y, 3.0 * x + 2.0 * y});
        }
    return triangulate(points).mesh;
}

TEST(TinLocator, FindsTheTriangleHoldingAPoint_AndNoneOutsideTheHull) {
    const TinMesh mesh = planeGrid();
    TinLocator locator(mesh);
    EXPECT_TRUE(locator.locate({1012.5, 2031.25}).has_value());
    EXPECT_TRUE(locator.locate({1000.0, 2000.0}).has_value()); // a hull corner
    EXPECT_TRUE(locator.locate({1040.0, 2020.0}).has_value()); // on a hull edge
    EXPECT_FALSE(locator.locate({999.999, 2020.0}).has_value());
    EXPECT_FALSE(locator.locate({1020.0, 2040.0 + 1e-9}).has_value());
}

TEST(TinLocator, ElevationIsTheTinsLinearSurface) {
    const TinMesh mesh = planeGrid();
    TinLocator locator(mesh);
    for (const Point2 p : {Point2{1012.5, 2031.25}, Point2{1000.0, 2000.0}, Point2{1039.0, 2001.0}})
        EXPECT_NEAR(*locator.elevation(p), 3.0 * p.x + 2.0 * p.y, 1e-9);
    EXPECT_FALSE(locator.elevation({1050.0, 2000.0}).has_value());
}

// The same triangles, each with its corners (and their neighbours) stored from the next corner.
TinMesh rotatedCorners(TinMesh mesh) {
    for (std::size_t t = 0; t < mesh.triangleCount(); ++t) {
        std::rotate(mesh.triangles.begin() + static_cast<std::ptrdiff_t>(3 * t),
                    mesh.triangles.begin() + static_cast<std::ptrdiff_t>(3 * t + 1),
                    mesh.triangles.begin() + static_cast<std::ptrdiff_t>(3 * t + 3));
        std::rotate(mesh.neighbours.begin() + static_cast<std::ptrdiff_t>(3 * t),
                    mesh.neighbours.begin() + static_cast<std::ptrdiff_t>(3 * t + 1),
                    mesh.neighbours.begin() + static_cast<std::ptrdiff_t>(3 * t + 3));
    }
    return mesh;
}

TEST(TinLocator, ElevationIn_TheSameBitsForEitherTriangleOfAnEdgeAndAnyFirstCorner) {
    // Regression: a breakline vertex where the DEM has no value (or in a point cloud) took the
    // TIN's z from the triangle the walk found, from its first stored corner on; both follow the
    // numbering of the triangles, which differs with the threads that built the TIN, and the
    // vertex's z differed in the last bit between 1 and 2 threads.
    std::mt19937_64 random(21);
    std::uniform_real_distribution<double> elevation(100.0, 2000.0);
    std::vector<Point3> points;
    for (int row = 0; row < 12; ++row)
        for (int col = 0; col < 12; ++col) // a grid: its edges' quarter points are exact
            points.push_back({1000.0 + 8.0 * col, 2000.0 + 8.0 * row, elevation(random)});
    const TinMesh mesh = triangulate(points).mesh;
    const TinMesh rotated = rotatedCorners(mesh);
    TinLocator locator(mesh);
    TinLocator rotatedLocator(rotated);
    std::size_t edgePoints = 0;
    for (std::uint32_t t = 0; t < mesh.triangleCount(); ++t)
        for (std::size_t i = 0; i < 3; ++i) {
            const Point3& a = mesh.vertices[mesh.triangles[3 * t + i]];
            const Point3& b = mesh.vertices[mesh.triangles[3 * t + (i + 1) % 3]];
            const Point3& c = mesh.vertices[mesh.triangles[3 * t + (i + 2) % 3]];
            const Point2 inside{(a.x + b.x + c.x) / 3.0, (a.y + b.y + c.y) / 3.0};
            EXPECT_EQ(locator.elevationIn(t, inside), rotatedLocator.elevationIn(t, inside));
            EXPECT_EQ(locator.elevationIn(t, {a.x, a.y}), a.z);
            const Point2 onEdge{a.x + 0.25 * (b.x - a.x), a.y + 0.25 * (b.y - a.y)};
            ASSERT_EQ(predicates::orient2d({a.x, a.y}, {b.x, b.y}, onEdge), 0.0);
            const double z = locator.elevationIn(t, onEdge);
            EXPECT_EQ(rotatedLocator.elevationIn(t, onEdge), z);
            const std::int32_t across = mesh.neighbours[3 * t + i];
            if (across < 0)
                continue;
            EXPECT_EQ(locator.elevationIn(static_cast<std::uint32_t>(across), onEdge), z)
                << "triangles " << t << " and " << across;
            ++edgePoints;
        }
    EXPECT_GT(edgePoints, 500U);
}

TEST(TinLocator, ClipsToTheHull_KeepingInsideParts) {
    const TinMesh mesh = planeGrid();
    TinLocator locator(mesh);
    // In, out through the right side, back in: two parts, each cut on the hull.
    const std::vector<Point3> line{{1010, 2010, 1}, {1060, 2015, 2}, {1030, 2035, 3}};
    const auto parts = locator.clipToHull(line);
    ASSERT_EQ(parts.size(), 2U);
    EXPECT_EQ(parts[0].front(), line[0]);
    EXPECT_NEAR(parts[0].back().x, 1040.0, 1e-9);
    EXPECT_NEAR(parts[0].back().y, 2013.0, 1e-9);
    EXPECT_NEAR(parts[0].back().z, 1.6, 1e-9); // z along the segment
    EXPECT_EQ(parts[1].back(), line[2]);
    // Both ends outside, crossing the whole hull: one part between the two sides.
    const auto across = locator.clipToHull({{990, 2020, 0}, {1050, 2020, 0}});
    ASSERT_EQ(across.size(), 1U);
    EXPECT_NEAR(across[0][0].x, 1000.0, 1e-9);
    EXPECT_NEAR(across[0][1].x, 1040.0, 1e-9);
    // Wholly outside, and one point alone: nothing.
    EXPECT_TRUE(locator.clipToHull({{900, 1900, 0}, {950, 1990, 0}}).empty());
    EXPECT_TRUE(locator.clipToHull({{1010, 2010, 0}}).empty());
}

TEST(TinLocator, EveryClippedPointIsInsideByTheExactTest_OnRandomLinesAcrossAGaussCloud) {
    const std::vector<Point3> points = test::generatePoints(test::Distribution::Gauss, 2000, 7);
    const TinMesh mesh = triangulate(points).mesh;
    TinLocator locator(mesh);
    std::mt19937_64 random(11);
    std::uniform_real_distribution<double> coordinate(-0.5, 1.5);
    std::size_t cut = 0;
    for (int line = 0; line < 300; ++line) {
        std::vector<Point3> polyline;
        for (int i = 0; i < 4; ++i)
            polyline.push_back({coordinate(random), coordinate(random), 0.0});
        for (const std::vector<Point3>& part : locator.clipToHull(polyline)) {
            ASSERT_GE(part.size(), 2U);
            for (const Point3& p : part)
                ASSERT_TRUE(locator.locate({p.x, p.y}).has_value()) << p.x << " " << p.y;
            cut += part.size();
        }
    }
    EXPECT_GT(cut, 100U);
}

bool holds(const TinMesh& mesh, std::uint32_t triangle, const Point3& p) {
    for (std::size_t i = 0; i < 3; ++i) {
        const Point3& a = mesh.vertices[mesh.triangles[3 * triangle + i]];
        const Point3& b = mesh.vertices[mesh.triangles[3 * triangle + (i + 1) % 3]];
        if (predicates::orient2d({a.x, a.y}, {b.x, b.y}, {p.x, p.y}) < 0.0)
            return false;
    }
    return true;
}

// A point clipToSurface left unlocated must have had a z, follow a point of its part, and be
// inside by the exact test.
TEST(TinLocator, ClipToSurface_LocatesEachPointOnce_AndIsTheSameOnAnyThreads) {
    const std::vector<Point3> points = test::generatePoints(test::Distribution::Gauss, 3000, 4);
    const TinMesh mesh = triangulate(points).mesh;
    std::mt19937_64 random(12);
    std::uniform_real_distribution<double> coordinate(-0.5, 1.5);
    std::vector<std::vector<Point3>> lines(200);
    for (std::size_t k = 0; k < lines.size(); ++k)
        for (int i = 0; i < 5; ++i) // the odd lines without z
            lines[k].push_back(
                {coordinate(random), coordinate(random), k % 2 == 1 ? std::nan("") : 7.0});
    TinLocator locator(mesh);
    const auto one = locator.clipToSurface(lines, 1);
    const auto three = locator.clipToSurface(lines, 3);
    ASSERT_EQ(one.size(), lines.size());
    std::size_t located = 0;
    std::size_t unlocated = 0;
    for (std::size_t k = 0; k < lines.size(); ++k) {
        const std::vector<std::vector<Point3>> hull = locator.clipToHull(lines[k]);
        ASSERT_EQ(one[k].size(), hull.size());
        ASSERT_EQ(three[k].size(), hull.size());
        for (std::size_t part = 0; part < hull.size(); ++part) {
            const TinLocator::LocatedPolyline& a = one[k][part];
            EXPECT_EQ(a.triangles, three[k][part].triangles);
            ASSERT_EQ(a.points.size(), hull[part].size());
            ASSERT_EQ(a.triangles.size(), hull[part].size());
            for (std::size_t i = 0; i < a.points.size(); ++i) {
                const Point3& p = a.points[i];
                EXPECT_EQ(p, three[k][part].points[i]);
                EXPECT_EQ(p.x, hull[part][i].x);
                EXPECT_EQ(p.y, hull[part][i].y);
                if (a.triangles[i] == TinLocator::kUnlocated) {
                    EXPECT_GT(i, 0U);
                    EXPECT_FALSE(std::isnan(hull[part][i].z));
                    EXPECT_TRUE(locator.locate({p.x, p.y}).has_value());
                    EXPECT_EQ(p.z, hull[part][i].z);
                    ++unlocated;
                    continue;
                }
                EXPECT_TRUE(holds(mesh, a.triangles[i], p));
                if (std::isnan(hull[part][i].z))
                    EXPECT_EQ(p.z, locator.elevationIn(a.triangles[i], {p.x, p.y}));
                else
                    EXPECT_EQ(p.z, hull[part][i].z);
                ++located;
            }
        }
    }
    EXPECT_GT(located, 200U);
    EXPECT_GT(unlocated, 0U);
}

/// Polylines of random points over the box [low, high]^2 and beyond it by half its side.
std::vector<std::vector<Point3>> randomLinesOver(double low, double high, std::size_t count,
                                                 std::uint64_t seed) {
    std::mt19937_64 random(seed);
    const double margin = (high - low) / 2;
    std::uniform_real_distribution<double> coordinate(low - margin, high + margin);
    std::vector<std::vector<Point3>> lines(count);
    for (std::vector<Point3>& line : lines)
        for (int i = 0; i < 4; ++i)
            line.push_back({coordinate(random), coordinate(random), 1.0});
    return lines;
}

// The hull found by a walk round it (Use::coversConvexHull) must be the pass's, edge for edge:
// clipToHull cuts every line at the same bits. A coarse grid for few far queries
// (Use::farQueries) locates the same points, each in a triangle that holds it.
TEST(TinLocator, AWalkRoundTheHull_AndACoarseGrid_ClipAndLocateAsThePassAndTheFineGrid) {
    std::vector<std::vector<Point3>> pointSets;
    for (const test::Distribution distribution : bench::kAllDistributions)
        pointSets.push_back(test::generatePoints(distribution, 20000, 21));
    std::vector<Point3> grid; // collinear points all along the hull
    for (int row = 0; row < 140; ++row)
        for (int col = 0; col < 140; ++col)
            grid.push_back({col / 139.0, row / 139.0, 0.0});
    pointSets.push_back(grid);
    pointSets.push_back(
        test::offset(test::generatePoints(test::Distribution::Uniform, 20000, 22), 1e6, 1e6));
    for (std::size_t set = 0; set < pointSets.size(); ++set) {
        SCOPED_TRACE("point set " + std::to_string(set));
        const TinMesh mesh = triangulate(pointSets[set]).mesh;
        const double offset = set + 1 == pointSets.size() ? 1e6 : 0.0;
        const std::vector<std::vector<Point3>> lines =
            randomLinesOver(offset, offset + 1.0, 300, 23 + set);
        TinLocator pass(mesh, TinLocator::Use{.threads = 2});
        // 400 buckets (a far query's four) where the fine grid has about 2,500.
        TinLocator walked(mesh, {.threads = 2, .coversConvexHull = true, .farQueries = 100});
        std::size_t cut = 0;
        for (const std::vector<Point3>& line : lines) {
            const std::vector<std::vector<Point3>> expected = pass.clipToHull(line);
            ASSERT_EQ(walked.clipToHull(line), expected);
            cut += expected.size();
        }
        EXPECT_GT(cut, 100U);
        const auto fine = pass.clipToSurface(lines, 2);
        const auto coarse = walked.clipToSurface(lines, 2);
        ASSERT_EQ(coarse.size(), fine.size());
        for (std::size_t k = 0; k < fine.size(); ++k) {
            ASSERT_EQ(coarse[k].size(), fine[k].size());
            for (std::size_t part = 0; part < fine[k].size(); ++part) {
                ASSERT_EQ(coarse[k][part].points, fine[k][part].points);
                for (std::size_t i = 0; i < coarse[k][part].points.size(); ++i) {
                    const std::uint32_t t = coarse[k][part].triangles[i];
                    if (t == TinLocator::kUnlocated) {
                        EXPECT_GT(i, 0U); // a part's first point is always located
                    } else {
                        EXPECT_TRUE(holds(mesh, t, coarse[k][part].points[i]));
                    }
                }
            }
        }
    }
}

TEST(TinLocator, IsTheSameBuiltOnAnyThreads) {
    // Enough triangles for the construction's loops to run on several threads.
    const std::vector<Point3> points = test::generatePoints(test::Distribution::Uniform, 60000, 6);
    const TinMesh mesh = triangulate(points).mesh;
    std::mt19937_64 random(13);
    std::uniform_real_distribution<double> coordinate(-0.2, 1.2);
    std::vector<std::vector<Point3>> lines(100);
    for (std::vector<Point3>& line : lines)
        for (int i = 0; i < 6; ++i)
            line.push_back({coordinate(random), coordinate(random), std::nan("")});
    const auto one = TinLocator(mesh, 1).clipToSurface(lines, 1);
    const auto four = TinLocator(mesh, 4).clipToSurface(lines, 1);
    ASSERT_EQ(one.size(), four.size());
    for (std::size_t k = 0; k < one.size(); ++k) {
        ASSERT_EQ(one[k].size(), four[k].size());
        for (std::size_t part = 0; part < one[k].size(); ++part) {
            EXPECT_EQ(one[k][part].points, four[k][part].points);
            EXPECT_EQ(one[k][part].triangles, four[k][part].triangles);
        }
    }
}

} // namespace
} // namespace terratin

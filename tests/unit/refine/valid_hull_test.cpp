// Which points lie outside a convex hull: the bisection over the fan against every edge's
// exact test, on random polygons, on their corners and edges, and far from the origin.

#include "valid_hull.hpp"

#include "terratin/geometry/predicates.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

namespace terratin::detail {
namespace {

// Outside when p lies on the right of any edge: the definition, edge by edge.
bool outsideAnyEdge(const std::vector<Point2>& corners, Point2 p) {
    for (std::size_t i = 0; i < corners.size(); ++i)
        if (predicates::orient2d(corners[i], corners[(i + 1) % corners.size()], p) < 0.0)
            return true;
    return false;
}

// A convex polygon of `n` corners on a circle of radius 100 around `centre` (random angles,
// counter-clockwise), on the integer lattice so that points on its edges can be made exactly.
std::vector<Point2> randomConvexPolygon(std::mt19937_64& random, std::size_t n, Point2 centre) {
    std::uniform_real_distribution<double> angle(0.0, 2.0 * std::numbers::pi);
    std::vector<double> angles(n);
    for (double& a : angles)
        a = angle(random);
    std::sort(angles.begin(), angles.end());
    std::vector<Point2> corners;
    for (const double a : angles) {
        const Point2 p{centre.x + std::round(100.0 * std::cos(a)),
                       centre.y + std::round(100.0 * std::sin(a))};
        // Rounding may make corners collinear or reflex, or repeat one: keep the strictly
        // convex ones.
        while (corners.size() >= 2 &&
               predicates::orient2d(corners[corners.size() - 2], corners.back(), p) <= 0.0)
            corners.pop_back();
        if (corners.empty() || corners.back() != p)
            corners.push_back(p);
    }
    while (corners.size() >= 3 &&
           (predicates::orient2d(corners[corners.size() - 2], corners.back(), corners[0]) <= 0.0 ||
            predicates::orient2d(corners.back(), corners[0], corners[1]) <= 0.0)) {
        if (predicates::orient2d(corners[corners.size() - 2], corners.back(), corners[0]) <= 0.0)
            corners.pop_back();
        else
            corners.erase(corners.begin());
    }
    return corners;
}

TEST(OutsideConvexPolygon, AgreesWithEveryEdgesTest_OnRandomPolygonsAndPoints) {
    std::mt19937_64 random(20261127);
    std::size_t outside = 0;
    std::size_t onBoundary = 0;
    for (const Point2 centre : {Point2{0.0, 0.0}, Point2{1e6, -3e6}}) {
        for (int polygon = 0; polygon < 200; ++polygon) {
            const std::vector<Point2> corners =
                randomConvexPolygon(random, 3 + static_cast<std::size_t>(polygon % 40), centre);
            ASSERT_GE(corners.size(), 3U);
            std::uniform_real_distribution<double> offset(-130.0, 130.0);
            std::vector<Point2> points;
            for (int k = 0; k < 200; ++k)
                points.push_back({centre.x + offset(random), centre.y + offset(random)});
            // Every corner, and lattice points on every edge and on its line beyond.
            for (std::size_t i = 0; i < corners.size(); ++i) {
                const Point2 a = corners[i];
                const Point2 b = corners[(i + 1) % corners.size()];
                points.push_back(a);
                for (const double t : {0.5, -1.0, 2.0})
                    points.push_back({a.x + t * (b.x - a.x), a.y + t * (b.y - a.y)});
            }
            for (const Point2 p : points) {
                const bool expected = outsideAnyEdge(corners, p);
                ASSERT_EQ(outsideConvexPolygon(corners, p), expected)
                    << "corners " << corners.size() << ", point (" << p.x << ", " << p.y << ")";
                outside += expected ? 1 : 0;
                bool onEdge = false;
                for (std::size_t i = 0; i < corners.size(); ++i)
                    onEdge |= predicates::orient2d(corners[i], corners[(i + 1) % corners.size()],
                                                   p) == 0.0;
                onBoundary += !expected && onEdge ? 1 : 0;
            }
        }
    }
    // Both answers, and points on the boundary (inside), were asked.
    EXPECT_GT(outside, 10000U);
    EXPECT_GT(onBoundary, 1000U);
}

TEST(OutsideConvexPolygon, ATriangle_ItsCornersAndEdgesAreInside) {
    const std::vector<Point2> triangle{{0.0, 0.0}, {4.0, 0.0}, {0.0, 4.0}};
    EXPECT_FALSE(outsideConvexPolygon(triangle, {1.0, 1.0}));
    EXPECT_FALSE(outsideConvexPolygon(triangle, {4.0, 0.0}));
    EXPECT_FALSE(outsideConvexPolygon(triangle, {2.0, 2.0})); // on the long edge
    EXPECT_FALSE(outsideConvexPolygon(triangle, {0.0, 2.0}));
    EXPECT_TRUE(outsideConvexPolygon(triangle, {2.0, 2.0 + 1e-12}));
    EXPECT_TRUE(outsideConvexPolygon(triangle, {-1e-300, 1.0}));
    EXPECT_TRUE(outsideConvexPolygon(triangle, {5.0, 0.0})); // on an edge's line, beyond it
}

} // namespace
} // namespace terratin::detail

// incircle on a lattice (lattice_incircle.hpp): the integer determinant gives the exact stage's
// sign wherever it answers, and it answers for exactly the differences it can hold.

#include "lattice_incircle.hpp"

#include "terratin/geometry/predicates.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <limits>
#include <random>

namespace terratin {
namespace {

using predicates::detail::incircleExact;
using predicates::detail::kLatticeBits;

/// The lattice stage for four points whose differences are exact (as the predicates check before
/// asking it; every point here has them).
std::optional<double> latticeIncircle(const Point2& a, const Point2& b, const Point2& c,
                                      const Point2& d) {
    return predicates::detail::latticeIncircle(a.x - d.x, a.y - d.y, b.x - d.x, b.y - d.y,
                                               c.x - d.x, c.y - d.y);
}

int signOf(double value) {
    return (value > 0.0) - (value < 0.0);
}

/// Points (x0 + i * unit, y0 + j * unit) for integers i, j.
Point2 onGrid(double x0, double y0, double unit, std::int64_t i, std::int64_t j) {
    return {x0 + static_cast<double>(i) * unit, y0 + static_cast<double>(j) * unit};
}

/// latticeIncircle answers, with the exact stage's sign.
void expectExactSign(const Point2& a, const Point2& b, const Point2& c, const Point2& d) {
    const std::optional<double> sign = latticeIncircle(a, b, c, d);
    ASSERT_TRUE(sign.has_value()) << a.x << " " << a.y;
    EXPECT_EQ(signOf(*sign), signOf(incircleExact(a, b, c, d)))
        << a.x << "," << a.y << " " << b.x << "," << b.y << " " << c.x << "," << c.y << " " << d.x
        << "," << d.y;
}

TEST(LatticeIncircle, GivesTheExactSign_OnGridsOfEveryScaleAndOffset) {
    // Cell sizes from 2^-20 to 2^10 and 30 m, origins from 0 to UTM northings and Mt Hood's
    // (no binary fraction: its centres lie on no lattice, their differences do), cell indices
    // up to a few thousand: every DEM frame the build meets, and cocircular points among them.
    std::mt19937_64 rng(7);
    std::uniform_int_distribution<std::int64_t> index(-3000, 3000);
    std::uniform_int_distribution<int> near(-3, 3);
    for (const double unit : {std::ldexp(1.0, -20), 0.5, 1.0, 30.0, 1024.0}) {
        for (const double origin : {0.0, 455005.0, 5102605.0, 587049.617315754061565}) {
            // Mt Hood's 3000 cells of 1024 m would leave the origin's binade, where its centres
            // are rounded: no lattice (and no DEM).
            if (origin == 587049.617315754061565 && unit > 30.0)
                continue;
            for (int trial = 0; trial < 400; ++trial) {
                // A circle through lattice points: centre (i, j), the radius-5 points around it,
                // one of them moved by a cell now and then (near-cocircular).
                const std::int64_t i = index(rng);
                const std::int64_t j = index(rng);
                const int move = trial % 3 == 0 ? near(rng) : 0;
                const Point2 a = onGrid(origin, origin, unit, i + 5, j);
                const Point2 b = onGrid(origin, origin, unit, i + 3, j + 4);
                const Point2 c = onGrid(origin, origin, unit, i - 4, j + 3);
                const Point2 d = onGrid(origin, origin, unit, i, j - 5 + move);
                expectExactSign(a, b, c, d);
                expectExactSign(d, c, b, a);
                // And four points anywhere on the grid.
                expectExactSign(onGrid(origin, origin, unit, index(rng), index(rng)),
                                onGrid(origin, origin, unit, index(rng), index(rng)),
                                onGrid(origin, origin, unit, index(rng), index(rng)),
                                onGrid(origin, origin, unit, index(rng), index(rng)));
            }
        }
    }
}

TEST(LatticeIncircle, GivesTheExactSign_AtTheLargestDifferencesItTakes) {
    // Coordinates of magnitude up to 2^29 - 1 units, differences up to 2^30 - 2: the largest
    // lifted terms, no overflow.
    const double largest = std::ldexp(1.0, kLatticeBits - 1) - 1.0;
    std::mt19937_64 rng(11);
    std::uniform_int_distribution<int> pick(0, 3);
    const std::array<double, 4> extremes{largest, -largest, largest - 1.0, -(largest - 1.0)};
    for (int trial = 0; trial < 2000; ++trial) {
        std::array<Point2, 4> p{};
        for (Point2& point : p)
            point = {extremes[static_cast<std::size_t>(pick(rng))],
                     extremes[static_cast<std::size_t>(pick(rng))]};
        expectExactSign(p[0], p[1], p[2], p[3]);
    }
    // Cocircular at the extremes: a rectangle and a circle of radius 5 near the corner.
    expectExactSign({largest, largest}, {-largest, largest}, {-largest, -largest},
                    {largest, -largest});
    const double centre = largest - 5.0;
    expectExactSign({centre + 5, centre}, {centre + 3, centre + 4}, {centre - 4, centre + 3},
                    {centre, centre - 5});
}

TEST(LatticeIncircle, LeavesOtherPointsToTheAdaptiveStages) {
    const Point2 a{0.0, 0.0};
    const Point2 b{1.0, 0.0};
    const Point2 c{0.0, 1.0};
    const double tooLarge = std::ldexp(1.0, kLatticeBits);
    EXPECT_TRUE(latticeIncircle(a, b, c, {tooLarge - 1.0, 1.0}).has_value());
    EXPECT_FALSE(latticeIncircle(a, b, c, {tooLarge, 1.0}).has_value());
    // A difference of 2^30 units in the scale the finest one sets.
    EXPECT_TRUE(latticeIncircle(a, b, {0.0, std::ldexp(1.0, 1 - kLatticeBits)}, {1.0, 1.0}));
    EXPECT_FALSE(latticeIncircle(a, b, {0.0, std::ldexp(1.0, -kLatticeBits)}, {1.0, 1.0}));
    // A LiDAR-like coordinate: its whole significand is used.
    EXPECT_FALSE(latticeIncircle(a, b, c, {0.1, 0.7}).has_value());
    EXPECT_FALSE(latticeIncircle(a, b, c, {455005.123456789, 1.0}).has_value());
    const double subnormal = std::numeric_limits<double>::denorm_min();
    EXPECT_FALSE(latticeIncircle(a, b, c, {subnormal, 1.0}).has_value());
    EXPECT_FALSE(latticeIncircle(a, b, c, {std::nan(""), 1.0}).has_value());
    EXPECT_FALSE(latticeIncircle(a, b, c, {INFINITY, 1.0}).has_value());
    // Four times the origin: on every circle through it.
    ASSERT_TRUE(latticeIncircle(a, a, a, a).has_value());
    EXPECT_EQ(*latticeIncircle(a, a, a, a), 0.0);
}

TEST(LatticeIncircle, Incircle_StillExact_OnCocircularGridPointsThatAreNoRectangle) {
    // What the lattice path is for: cell centres of a 30 m UTM grid on one circle, the corners
    // of no axis-aligned rectangle, in all four positions of the tested point.
    const double x0 = 455005.0;
    const double y0 = 5102605.0;
    const std::array<Point2, 4> p{onGrid(x0, y0, 30.0, 5, 0), onGrid(x0, y0, 30.0, 3, 4),
                                  onGrid(x0, y0, 30.0, -4, 3), onGrid(x0, y0, 30.0, 0, -5)};
    EXPECT_EQ(predicates::incircle(p[0], p[1], p[2], p[3]), 0.0);
    EXPECT_EQ(predicates::incircle(p[1], p[2], p[3], p[0]), 0.0);
    const Point2 inside = onGrid(x0, y0, 30.0, 4, 0);
    const Point2 outside = onGrid(x0, y0, 30.0, 6, 0);
    EXPECT_GT(predicates::incircle(p[0], p[1], p[2], inside), 0.0);
    EXPECT_LT(predicates::incircle(p[0], p[1], p[2], outside), 0.0);
}

} // namespace
} // namespace terratin

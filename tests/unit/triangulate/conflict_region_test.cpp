// The circum-circle method's region filter: a circle may only be said to miss a box it
// really misses, or the conflict test would skip workers it has to ask.

#include "conflict_region.hpp"

#include "terratin/geometry/predicates.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace terratin {
namespace {

using detail::Box;
using detail::Circle;

Box boxAround(const Point2& p, double halfWidth) {
    Box box;
    box.add(Point2{p.x - halfWidth, p.y - halfWidth});
    box.add(Point2{p.x + halfWidth, p.y + halfWidth});
    return box;
}

TEST(ConflictRegion, CircumcircleGoesThroughTheThreeCorners) {
    const Circle circle = Circle::through({0.0, 0.0}, {2.0, 0.0}, {0.0, 2.0});
    EXPECT_DOUBLE_EQ(circle.x, 1.0);
    EXPECT_DOUBLE_EQ(circle.y, 1.0);
    EXPECT_DOUBLE_EQ(circle.radius2, 2.0);
}

TEST(ConflictRegion, CollinearCornersGiveTheWholePlane) {
    const Circle circle = Circle::through({0.0, 0.0}, {1.0, 1.0}, {2.0, 2.0});
    EXPECT_TRUE(std::isinf(circle.radius2));
    EXPECT_TRUE(circle.mayReach(boxAround({1e9, -1e9}, 1.0)));
}

TEST(ConflictRegion, MissesOnlyBoxesOutsideTheDisc) {
    const Circle circle = Circle::through({0.0, 0.0}, {2.0, 0.0}, {0.0, 2.0});
    EXPECT_TRUE(circle.mayReach(boxAround({1.0, 1.0}, 0.1)));   // around the centre
    EXPECT_TRUE(circle.mayReach(boxAround({-5.0, 1.0}, 10.0))); // holding the whole disc
    EXPECT_TRUE(circle.mayReach(boxAround({2.05, 2.05}, 0.1))); // a corner inside the disc
    EXPECT_FALSE(circle.mayReach(boxAround({2.5, 2.5}, 0.1)));  // beyond it diagonally
    EXPECT_FALSE(circle.mayReach(boxAround({1.0, 4.0}, 0.5)));
    EXPECT_FALSE(circle.mayReach(Box{})); // an empty region
}

// Random triangles and boxes: whenever a box corner lies strictly inside the exact
// circumcircle (decided by the sign of the in-circle determinant), the filter must say the
// circle may reach the box.
TEST(ConflictRegion, NeverMissesABoxWithAPointInsideTheCircle) {
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> coordinate(-1.0, 1.0);
    std::uniform_real_distribution<double> width(0.0, 0.05);
    int reached = 0;
    for (int trial = 0; trial < 20000; ++trial) {
        Point2 a{coordinate(rng), coordinate(rng)};
        Point2 b{coordinate(rng), coordinate(rng)};
        const Point2 c{coordinate(rng), coordinate(rng)};
        if (predicates::orient2d(a, b, c) < 0)
            std::swap(a, b);
        const Circle circle = Circle::through(a, b, c);
        const Point2 corner{coordinate(rng), coordinate(rng)};
        Box box;
        box.add(corner);
        box.add(Point2{corner.x + width(rng), corner.y + width(rng)});
        if (predicates::incircle(a, b, c, corner) > 0) {
            ASSERT_TRUE(circle.mayReach(box)) << trial;
            ++reached;
        }
    }
    EXPECT_GT(reached, 1000);
}

} // namespace
} // namespace terratin

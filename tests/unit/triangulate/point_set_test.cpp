#include "terratin/triangulate/point_set.hpp"

#include "terratin/error.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace terratin {
namespace {

TEST(PreparePoints, KeepsFirstOccurrenceOrder_WhenMergingDuplicates) {
    const std::vector<Point3> points{{2, 2, 1}, {0, 0, 2}, {2, 2, 3}, {1, 0, 4}, {0, 0, 5}};
    const PreparedPoints prepared = preparePoints(points, DuplicateZPolicy::First);
    EXPECT_EQ(prepared.duplicateCount, 2U);
    EXPECT_EQ(prepared.sourceIndex, (std::vector<std::uint32_t>{0, 1, 3}));
    EXPECT_EQ(prepared.z, (std::vector<double>{1, 2, 4}));
}

TEST(PreparePoints, ShiftsExactly_WhenCoordinatesAreLarge) {
    const std::vector<Point3> points{
        {500000.125, 5000000.5, 0}, {500030.0, 5000000.5, 0}, {500000.125, 4999970.25, 0}};
    const PreparedPoints prepared = preparePoints(points, DuplicateZPolicy::First);
    EXPECT_NE(prepared.origin.x, 0.0);
    EXPECT_NE(prepared.origin.y, 0.0);
    for (std::size_t i = 0; i < points.size(); ++i) {
        EXPECT_EQ(prepared.local[i].x + prepared.origin.x, points[i].x);
        EXPECT_EQ(prepared.local[i].y + prepared.origin.y, points[i].y);
        EXPECT_LT(std::abs(prepared.local[i].x), 100.0);
    }
}

TEST(PreparePoints, KeepsZeroOrigin_WhenAShiftWouldRound) {
    // 1e-50 - c is not representable for any c of the size of 1e6: no shift is exact.
    const std::vector<Point3> points{{1e-50, 0, 0}, {2e6, 0, 0}, {0, 2e6, 0}};
    const PreparedPoints prepared = preparePoints(points, DuplicateZPolicy::First);
    EXPECT_EQ(prepared.origin.x, 0.0);
    EXPECT_EQ(prepared.local[0].x, 1e-50);
}

TEST(PreparePoints, Throws_WhenCoordinatesLeaveThePredicateRange) {
    const std::vector<Point3> tiny{{1e-300, 0, 0}, {2e6, 0, 0}, {0, 2e6, 0}};
    EXPECT_THROW(preparePoints(tiny, DuplicateZPolicy::First), InvalidInputError);
    const std::vector<Point3> huge{{1e80, 0, 0}, {-1e80, 0, 0}, {0, 1e80, 0}};
    EXPECT_THROW(preparePoints(huge, DuplicateZPolicy::First), InvalidInputError);
}

TEST(PreparePoints, Throws_WhenOnlyTwoDistinctPoints) {
    const std::vector<Point3> points{{0, 0, 0}, {1, 0, 0}, {1, 0, 1}};
    EXPECT_THROW(preparePoints(points, DuplicateZPolicy::First), InvalidInputError);
}

TEST(PreparePoints, Throws_WhenCoordinateIsInfinite) {
    const std::vector<Point3> points{
        {0, 0, 0}, {1, 0, 0}, {std::numeric_limits<double>::infinity(), 1, 0}};
    EXPECT_THROW(preparePoints(points, DuplicateZPolicy::First), InvalidInputError);
}

} // namespace
} // namespace terratin

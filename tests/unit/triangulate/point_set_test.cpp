#include "terratin/triangulate/point_set.hpp"

#include "terratin/error.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <utility>
#include <vector>

namespace terratin {
namespace {

// The elements of a prepared array (on huge pages), to compare with a plain vector.
template <class T, class Allocator>
std::vector<T> elements(const std::vector<T, Allocator>& array) {
    return {array.begin(), array.end()};
}

TEST(PreparePoints, KeepsFirstOccurrenceOrder_WhenMergingDuplicates) {
    const std::vector<Point3> points{{2, 2, 1}, {0, 0, 2}, {2, 2, 3}, {1, 0, 4}, {0, 0, 5}};
    const PreparedPoints prepared = preparePoints(points, DuplicateZPolicy::First);
    EXPECT_EQ(prepared.duplicateCount, 2U);
    EXPECT_EQ(elements(prepared.sourceIndex), (std::vector<std::uint32_t>{0, 1, 3}));
    EXPECT_EQ(elements(prepared.z), (std::vector<double>{1, 2, 4}));
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

// Points on a coarse lattice, so that about half repeat an earlier (x, y); some zeros are
// negative, which must merge with positive zeros.
std::vector<Point3> pointsWithManyDuplicates(std::size_t count) {
    std::vector<Point3> points;
    std::uint64_t state = 12345;
    const auto nextValue = [&state](std::uint64_t bound) {
        state = state * 6364136223846793005ULL + 1442695040888963407ULL;
        return (state >> 33U) % bound;
    };
    const double side = std::sqrt(static_cast<double>(count) / 2.0);
    for (std::size_t i = 0; i < count; ++i) {
        double x = static_cast<double>(nextValue(static_cast<std::uint64_t>(side)));
        const double y = static_cast<double>(nextValue(static_cast<std::uint64_t>(side)));
        if (x == 0.0 && nextValue(2) == 0)
            x = -0.0;
        points.push_back({x, y, static_cast<double>(nextValue(1000))});
    }
    return points;
}

// What every policy should give, from an ordered map of the groups.
PreparedPoints referencePreparation(const std::vector<Point3>& points, DuplicateZPolicy policy) {
    std::map<std::pair<double, double>, std::vector<std::uint32_t>> groups;
    for (std::uint32_t i = 0; i < points.size(); ++i)
        groups[{points[i].x == 0.0 ? 0.0 : points[i].x, points[i].y}].push_back(i);
    std::vector<std::vector<std::uint32_t>> byFirst;
    for (auto& [position, members] : groups)
        byFirst.push_back(members);
    std::sort(byFirst.begin(), byFirst.end());
    PreparedPoints reference;
    for (const std::vector<std::uint32_t>& members : byFirst) {
        std::uint32_t source = members.front();
        double z = points[source].z;
        for (std::size_t m = 1; m < members.size(); ++m) {
            const double other = points[members[m]].z;
            if (policy == DuplicateZPolicy::Last) {
                source = members[m];
                z = other;
            } else if (policy == DuplicateZPolicy::Min) {
                z = std::min(z, other);
            } else if (policy == DuplicateZPolicy::Max) {
                z = std::max(z, other);
            } else if (policy == DuplicateZPolicy::Mean) {
                z += other;
            }
        }
        if (policy == DuplicateZPolicy::Mean)
            z /= static_cast<double>(members.size());
        reference.sourceIndex.push_back(source);
        reference.z.push_back(z);
    }
    reference.duplicateCount = points.size() - byFirst.size();
    return reference;
}

TEST(PreparePoints, MergesLikeAReference_OnManyThreadsAndDuplicates) {
    // Enough points for several threads and many hash partitions.
    const std::vector<Point3> points = pointsWithManyDuplicates(150000);
    for (const DuplicateZPolicy policy :
         {DuplicateZPolicy::First, DuplicateZPolicy::Last, DuplicateZPolicy::Min,
          DuplicateZPolicy::Max, DuplicateZPolicy::Mean}) {
        const PreparedPoints reference = referencePreparation(points, policy);
        ASSERT_GT(reference.duplicateCount, points.size() / 4);
        for (const unsigned threads : {1U, 3U}) {
            SCOPED_TRACE(testing::Message()
                         << "policy " << static_cast<int>(policy) << ", " << threads << " threads");
            const PreparedPoints prepared = preparePoints(points, policy, threads);
            EXPECT_EQ(prepared.duplicateCount, reference.duplicateCount);
            EXPECT_EQ(prepared.sourceIndex, reference.sourceIndex);
            EXPECT_EQ(prepared.z, reference.z);
        }
    }
}

} // namespace
} // namespace terratin

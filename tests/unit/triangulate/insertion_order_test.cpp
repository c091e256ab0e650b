// The insertion orders: permutations of every vertex but the auxiliary corner, reproducible
// from the seed, and for BRIO rounds that grow towards the end with a spatially sorted
// sequence inside each round.

#include "insertion_order.hpp"

#include "point_distributions.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <span>
#include <vector>

namespace terratin {
namespace {

std::vector<Point2> planar(const std::vector<Point3>& points) {
    std::vector<Point2> result;
    result.reserve(points.size());
    for (const Point3& p : points)
        result.push_back({p.x, p.y});
    return result;
}

// True when `order` holds every id below `count` but `skip`, each once.
bool isPermutationWithout(std::span<const std::uint32_t> ids, std::uint32_t count,
                          std::uint32_t skip) {
    std::vector<std::uint32_t> order(ids.begin(), ids.end());
    std::vector<std::uint32_t> expected(count);
    std::iota(expected.begin(), expected.end(), 0U);
    expected.erase(expected.begin() + skip);
    std::sort(order.begin(), order.end());
    return order == expected;
}

double tourLength(const std::vector<Point2>& points, std::span<const std::uint32_t> order,
                  std::size_t begin, std::size_t end) {
    double length = 0.0;
    for (std::size_t i = begin + 1; i < end; ++i)
        length += std::hypot(points[order[i]].x - points[order[i - 1]].x,
                             points[order[i]].y - points[order[i - 1]].y);
    return length;
}

TEST(InsertionOrder, RandomOrderIsASeededPermutationWithoutTheSkippedVertex) {
    const auto order = detail::randomInsertionOrder(1000, 17, 5);
    EXPECT_TRUE(isPermutationWithout(order, 1000, 17));
    EXPECT_EQ(order, detail::randomInsertionOrder(1000, 17, 5));
    EXPECT_NE(order, detail::randomInsertionOrder(1000, 17, 6));
}

TEST(InsertionOrder, BrioIsASeededPermutationWithoutTheSkippedVertex) {
    const auto points = planar(test::generatePoints(test::Distribution::Gauss, 5000, 3));
    std::vector<std::size_t> roundStarts;
    const auto order = detail::brioInsertionOrder(points, 42, 9, &roundStarts);
    EXPECT_TRUE(isPermutationWithout(order, 5000, 42));
    EXPECT_EQ(order, detail::brioInsertionOrder(points, 42, 9));
    EXPECT_NE(order, detail::brioInsertionOrder(points, 42, 10));
    ASSERT_FALSE(roundStarts.empty());
    EXPECT_EQ(roundStarts.front(), 0U);
    EXPECT_TRUE(std::is_sorted(roundStarts.begin(), roundStarts.end()));
}

TEST(InsertionOrder, BrioRoundsGrowAndTheLastHoldsAboutHalfThePoints) {
    constexpr std::uint32_t kCount = 100000;
    const auto points = planar(test::generatePoints(test::Distribution::Uniform, kCount, 4));
    std::vector<std::size_t> roundStarts;
    const auto order = detail::brioInsertionOrder(points, 0, 1, &roundStarts);
    roundStarts.push_back(order.size());
    const std::size_t rounds = roundStarts.size() - 1;
    ASSERT_GE(rounds, 10U); // about log2(n) rounds
    const std::size_t last = roundStarts[rounds] - roundStarts[rounds - 1];
    EXPECT_NEAR(static_cast<double>(last) / kCount, 0.5, 0.01);
    const std::size_t secondLast = roundStarts[rounds - 1] - roundStarts[rounds - 2];
    EXPECT_NEAR(static_cast<double>(secondLast) / kCount, 0.25, 0.01);
    // The keys are computed in parallel blocks; the order must not depend on how many.
    for (const unsigned threads : {2U, 3U, 8U})
        EXPECT_EQ(detail::brioInsertionOrder(points, 0, 1, nullptr, threads), order);
}

TEST(InsertionOrder, BrioSortsEachRoundSpatially) {
    constexpr std::uint32_t kCount = 50000;
    const auto points = planar(test::generatePoints(test::Distribution::Uniform, kCount, 8));
    std::vector<std::size_t> roundStarts;
    const auto order = detail::brioInsertionOrder(points, 0, 1, &roundStarts);
    const auto random = detail::randomInsertionOrder(kCount, 0, 1);
    // The last round, about half the points: a Hilbert tour through m uniform points of the
    // unit square is O(sqrt(m)) long, a random tour about m / 2.
    const std::size_t begin = roundStarts.back();
    const std::size_t m = order.size() - begin;
    const double sorted = tourLength(points, order, begin, order.size());
    const double shuffled = tourLength(points, random, 0, m);
    EXPECT_LT(sorted, 2.0 * std::sqrt(static_cast<double>(m)));
    EXPECT_GT(shuffled, 0.4 * static_cast<double>(m));
}

} // namespace
} // namespace terratin

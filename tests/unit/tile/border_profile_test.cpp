// The vertices of a tile border: every valid run's ends, the bound over every valid cell
// (checked by borderProfileError and by an independent scan here), and no data respected.

#include "border_profile.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <stdexcept>
#include <vector>

namespace terratin::detail {
namespace {

constexpr float kNoData = std::numeric_limits<float>::quiet_NaN();

/// A random walk of `count` cells with gaps of no data, from a fixed seed.
std::vector<float> walkWithGaps(std::size_t count, std::uint64_t seed) {
    std::mt19937_64 rng(seed);
    std::normal_distribution<double> step(0.0, 2.0);
    std::uniform_int_distribution<int> gap(0, 60);
    std::vector<float> z(count);
    double height = 100.0;
    for (float& cell : z) {
        height += step(rng);
        cell = gap(rng) == 0 ? kNoData : static_cast<float>(height);
    }
    return z;
}

/// The largest error of a valid cell against the kept cells around it, written apart from the
/// library: each cell's neighbours among the kept found by a search outwards.
double independentError(const std::vector<float>& z, const std::vector<std::uint32_t>& kept) {
    std::vector<bool> isKept(z.size(), false);
    for (const std::uint32_t k : kept)
        isKept[k] = true;
    double largest = 0.0;
    for (std::size_t i = 0; i < z.size(); ++i) {
        if (std::isnan(z[i]) || isKept[i])
            continue;
        std::size_t left = i;
        while (!isKept[left]) {
            EXPECT_FALSE(std::isnan(z[left])) << "cell " << i << " has no kept cell on its left";
            --left;
        }
        std::size_t right = i;
        while (!isKept[right]) {
            EXPECT_FALSE(std::isnan(z[right])) << "cell " << i << " has no kept cell on its right";
            ++right;
        }
        const double t = static_cast<double>(i - left) / static_cast<double>(right - left);
        largest = std::max(largest, std::abs(z[i] - (z[left] + (z[right] - z[left]) * t)));
    }
    return largest;
}

TEST(BorderProfile, KeepsEveryRunsEnds_AndHoldsTheBound_OnRandomWalksWithGaps) {
    for (std::uint64_t seed = 1; seed <= 20; ++seed) {
        const std::vector<float> z = walkWithGaps(3000, seed);
        for (const double bound : {0.0, 0.5, 2.0, 10.0}) {
            const std::vector<std::uint32_t> kept = keptBorderCells(z, bound);
            ASSERT_TRUE(std::is_sorted(kept.begin(), kept.end()));
            for (std::size_t i = 0; i < z.size(); ++i) {
                const bool runStart = !std::isnan(z[i]) && (i == 0 || std::isnan(z[i - 1]));
                const bool runEnd =
                    !std::isnan(z[i]) && (i + 1 == z.size() || std::isnan(z[i + 1]));
                if (runStart || runEnd) {
                    EXPECT_TRUE(std::binary_search(kept.begin(), kept.end(), i)) << i;
                }
            }
            for (const std::uint32_t k : kept)
                EXPECT_FALSE(std::isnan(z[k]));
            EXPECT_LE(borderProfileError(z, kept), bound);
            EXPECT_LE(independentError(z, kept), bound);
        }
    }
}

TEST(BorderProfile, KeepsFewerCellsForALooserBound) {
    const std::vector<float> z = walkWithGaps(5000, 7);
    const std::size_t all = keptBorderCells(z, 0.0).size();
    const std::size_t tight = keptBorderCells(z, 1.0).size();
    const std::size_t loose = keptBorderCells(z, 20.0).size();
    EXPECT_LT(tight, all);
    EXPECT_LT(loose, tight);
}

TEST(BorderProfile, ASpikeInAFlatBorderKeepsItsFoot_AndGoesWithinTheBound) {
    std::vector<float> z(101, 5.0F);
    z[37] = 15.0F;
    // The line from the spike to an end would pass far above the flat cells beside it.
    EXPECT_EQ(keptBorderCells(z, 1.0), (std::vector<std::uint32_t>{0, 36, 37, 38, 100}));
    // Within the bound, the spike goes too.
    EXPECT_EQ(keptBorderCells(z, 10.0), (std::vector<std::uint32_t>{0, 100}));
}

TEST(BorderProfile, NoDataSplitsTheBorder_ALoneCellIsKept_AllNoDataKeepsNothing) {
    const std::vector<float> z{kNoData, 1.0F, 2.0F, 3.0F, kNoData, 7.0F, kNoData, kNoData};
    EXPECT_EQ(keptBorderCells(z, 0.5), (std::vector<std::uint32_t>{1, 3, 5}));
    EXPECT_TRUE(keptBorderCells(std::vector<float>(5, kNoData), 1.0).empty());
    EXPECT_TRUE(keptBorderCells(std::vector<float>{}, 1.0).empty());
}

TEST(BorderProfile, TheSameCellsGiveTheSameVertices) {
    const std::vector<float> z = walkWithGaps(2000, 3);
    EXPECT_EQ(keptBorderCells(z, 1.5), keptBorderCells(std::vector<float>(z), 1.5));
}

TEST(BorderProfile, RefusesANegativeOrNonFiniteBound) {
    const std::vector<float> z{1.0F, 2.0F};
    EXPECT_THROW((void)keptBorderCells(z, -1.0), std::invalid_argument);
    EXPECT_THROW((void)keptBorderCells(z, std::numeric_limits<double>::infinity()),
                 std::invalid_argument);
    EXPECT_THROW((void)keptBorderCells(z, std::numeric_limits<double>::quiet_NaN()),
                 std::invalid_argument);
}

} // namespace
} // namespace terratin::detail

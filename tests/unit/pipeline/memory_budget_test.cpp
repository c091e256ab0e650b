// --memory-limit's shares: the tile chosen is the largest that fits the limit at
// its worst, a tile size given is refused when it does not fit, and the least limit a refusal
// names is one that fits.

#include "memory_budget.hpp"

#include "terratin/error.hpp"

#include <gtest/gtest.h>

#include <regex>
#include <string>

namespace terratin::detail {
namespace {

constexpr std::uint64_t kMiB = std::uint64_t{1} << 20U;

std::string namer(std::string_view keyword) {
    return "--" + std::string(keyword);
}

std::string refusal(std::uint64_t limit, std::size_t margin, std::size_t tileSize) {
    try {
        memoryBudget(limit, margin, tileSize);
    } catch (InvalidInputError& error) {
        error.nameOptions(namer);
        return error.what();
    }
    return "<accepted>";
}

/// The limit a refusal names ("give 142M or more", "need --memory-limit 587M or more").
std::uint64_t namedLimit(const std::string& message) {
    std::smatch match;
    EXPECT_TRUE(std::regex_search(message, match, std::regex("(\\d+)M or more"))) << message;
    return std::stoull(match[1]) * kMiB;
}

TEST(MemoryBudget, TheTileChosenIsTheLargestThatFits) {
    for (const std::uint64_t limit : {256 * kMiB, 1024 * kMiB, 8192 * kMiB})
        for (const std::size_t margin : {0U, 1U, 50U}) {
            const MemoryBudget budget = memoryBudget(limit, margin, 0);
            EXPECT_GE(budget.tileSize, kLeastTileSize);
            EXPECT_EQ(memoryBudget(limit, margin, budget.tileSize).tileSize, budget.tileSize);
            EXPECT_NE(refusal(limit, margin, budget.tileSize + 1), "<accepted>");
            EXPECT_LE(budget.gdalCacheBytes + budget.writerBytes, limit / 2);
            // The tile's share is what the others leave, and the tile chosen takes most of it.
            EXPECT_LT(budget.gdalCacheBytes + budget.writerBytes + budget.tileBytes, limit);
            EXPECT_GT(budget.gdalCacheBytes + budget.writerBytes + budget.tileBytes,
                      limit - 128 * kMiB);
        }
    // More memory, larger tiles; a wider margin, smaller ones.
    EXPECT_LT(memoryBudget(512 * kMiB, 1, 0).tileSize, memoryBudget(2048 * kMiB, 1, 0).tileSize);
    EXPECT_GT(memoryBudget(512 * kMiB, 1, 0).tileSize, memoryBudget(512 * kMiB, 100, 0).tileSize);
}

TEST(MemoryBudget, ALimitTooSmall_NamesALimitThatIsEnough) {
    const std::string small = refusal(100 * kMiB, 1, 0);
    EXPECT_NE(small.find("--memory_limit 100M is too little"), std::string::npos) << small;
    // A limit of a few bytes is named as given, not rounded up to 1M.
    const std::string tiny = refusal(10, 1, 0);
    EXPECT_NE(tiny.find("--memory_limit 10 bytes is too little"), std::string::npos) << tiny;
    EXPECT_EQ(refusal(namedLimit(small), 1, 0), "<accepted>");
    EXPECT_NE(refusal(namedLimit(small) - 2 * kMiB, 1, 0), "<accepted>");

    const std::string large = refusal(256 * kMiB, 1, 4000);
    EXPECT_NE(large.find("tiles of 4000 cells need --memory_limit"), std::string::npos) << large;
    EXPECT_EQ(refusal(namedLimit(large), 1, 4000), "<accepted>");
}

} // namespace
} // namespace terratin::detail

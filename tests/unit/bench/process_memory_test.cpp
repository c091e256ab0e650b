// terratin-bench's memory helpers: the peak probe and the warm-up before each timed run.

#include "process_memory.hpp"

#include <gtest/gtest.h>

#include <cstddef>
#include <optional>

namespace terratin::bench {
namespace {

constexpr std::size_t kMiB = std::size_t{1} << 20U;

TEST(WarmFreeMemory, TouchesEveryPage_AndGivesTheMemoryBack) {
    PeakMemoryProbe probe;
    probe.start();
    const std::optional<std::size_t> before = residentBytes();
    if (!probe.peakGrowthBytes() || !before)
        GTEST_SKIP() << "this kernel does not let the process measure its resident set";
    constexpr std::size_t kWarmed = 96 * kMiB;
    warmFreeMemory(kWarmed);
    // Resolution of the peak: one page, but other threads of the test runner may allocate.
    EXPECT_GE(*probe.peakGrowthBytes(), kWarmed - 4 * kMiB);
    const std::optional<std::size_t> after = residentBytes();
    ASSERT_TRUE(after.has_value());
    EXPECT_LT(*after, *before + 16 * kMiB) << "the warmed memory was kept";
}

TEST(WarmFreeMemory, DoesNothingForZeroBytes) {
    PeakMemoryProbe probe;
    probe.start();
    if (!probe.peakGrowthBytes())
        GTEST_SKIP() << "this kernel does not let the process measure its resident set";
    warmFreeMemory(0);
    EXPECT_LT(*probe.peakGrowthBytes(), 4 * kMiB);
}

} // namespace
} // namespace terratin::bench

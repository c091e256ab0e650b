// terratin-bench's steal-time probe reads the all-CPU line of /proc/stat.

#include "host_steal.hpp"

#include <gtest/gtest.h>

#include <optional>

namespace terratin::bench {
namespace {

TEST(HostSteal, ReadsTheTotalAndStealOfTheAllCpuLine) {
    const std::optional<CpuTimes> times =
        parseCpuTimes("cpu  8484291 62692 573681 2831882 10014 0 2254 122599 0 0");
    ASSERT_TRUE(times.has_value());
    EXPECT_EQ(times->steal, 122599U);
    EXPECT_EQ(times->total, 8484291U + 62692U + 573681U + 2831882U + 10014U + 0U + 2254U + 122599U);
}

TEST(HostSteal, RefusesOtherLinesAndKernelsWithoutSteal) {
    EXPECT_FALSE(parseCpuTimes("cpu0 1 2 3 4 5 6 7 8 0 0").has_value());
    EXPECT_FALSE(parseCpuTimes("intr 12345").has_value());
    EXPECT_FALSE(parseCpuTimes("cpu  1 2 3 4 5 6 7").has_value()); // before Linux 2.6.11
    EXPECT_FALSE(parseCpuTimes("").has_value());
}

TEST(HostSteal, MeasuresAShareOfAtMostOneOnThisMachine) {
    HostStealProbe probe;
    probe.start();
    volatile double sink = 0.0;
    for (int i = 0; i < 20000000; ++i)
        sink = sink + 1.0; // let some ticks go by
    const std::optional<double> share = probe.stolenShare();
    if (share) { // Linux with ticks gone by
        EXPECT_GE(*share, 0.0);
        EXPECT_LE(*share, 1.0);
    }
}

} // namespace
} // namespace terratin::bench

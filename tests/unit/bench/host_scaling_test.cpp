#include "host_scaling.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace terratin::bench {
namespace {

TEST(HostScaling, SpeedUpIsThreadsTimesTheRatioOfTheTimes) {
    // Two threads doing twice the work in the same time: perfect scaling, 2.
    const std::vector<double> one{1.0};
    const std::vector<double> same{1.0};
    EXPECT_DOUBLE_EQ(medianSpeedUp(one, same, 2), 2.0);
    // In twice the time: the threads gained nothing, 1.
    const std::vector<double> twice{2.0};
    EXPECT_DOUBLE_EQ(medianSpeedUp(one, twice, 2), 1.0);
}

TEST(HostScaling, TakesTheMedianOfTheRounds) {
    const std::vector<double> one{1.0, 1.0, 1.0};
    const std::vector<double> all{1.0, 4.0, 1.6}; // speed-ups 2.0, 0.5, 1.25
    EXPECT_DOUBLE_EQ(medianSpeedUp(one, all, 2), 1.25);
    const std::vector<double> evenOne{1.0, 1.0};
    const std::vector<double> evenAll{1.0, 2.0}; // speed-ups 2 and 1
    EXPECT_DOUBLE_EQ(medianSpeedUp(evenOne, evenAll, 2), 1.5);
    EXPECT_EQ(medianSpeedUp({}, {}, 2), 0.0);
}

} // namespace
} // namespace terratin::bench

#pragma once
/// @file
/// Wall-clock time of a stage, for the timings of the build report. Internal to terratin.

#include <chrono>

namespace terratin::detail {

/// Started when made; seconds() is the wall-clock time since then.
class Stopwatch {
public:
    [[nodiscard]] double seconds() const {
        return std::chrono::duration<double>(Clock::now() - m_start).count();
    }

private:
    using Clock = std::chrono::steady_clock;
    Clock::time_point m_start = Clock::now();
};

} // namespace terratin::detail

#pragma once
// Timing and the median the tables report.

#include <algorithm>
#include <chrono>
#include <cstddef>
#include <stdexcept>
#include <vector>

namespace terratin::bench {

/// Wall-clock seconds since construction, on the monotonic clock.
class Stopwatch {
public:
    Stopwatch() : m_start(std::chrono::steady_clock::now()) {}

    [[nodiscard]] double seconds() const {
        return std::chrono::duration<double>(std::chrono::steady_clock::now() - m_start).count();
    }

private:
    std::chrono::steady_clock::time_point m_start;
};

/// The median of `samples` (the mean of the two middle values for an even count).
/// Throws std::invalid_argument when `samples` is empty. O(n log n).
inline double median(std::vector<double> samples) {
    if (samples.empty())
        throw std::invalid_argument("median of no samples");
    std::sort(samples.begin(), samples.end());
    const std::size_t middle = samples.size() / 2;
    if (samples.size() % 2 == 1)
        return samples[middle];
    return 0.5 * (samples[middle - 1] + samples[middle]);
}

} // namespace terratin::bench

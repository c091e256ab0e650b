#include "interleaved_runs.hpp"

#include "process_memory.hpp"
#include "stats.hpp"

#include <algorithm>
#include <optional>

namespace terratin::bench {

namespace {
// Warmed beyond a previous peak: runs of one configuration differ a little.
constexpr std::size_t kWarmMarginBytes = std::size_t{64} << 20U;
// The largest peak of any run of the process so far: what a job's first run warms.
std::size_t largestPeakBytes = 0;
} // namespace

void runInterleaved(std::span<TimedJob> jobs, unsigned rounds, bool warmMemory) {
    PeakMemoryProbe probe;
    for (unsigned round = 0; round < rounds; ++round) {
        for (TimedJob& job : jobs) {
            if (job.stopped)
                continue;
            if (warmMemory) {
                const std::size_t previousPeak =
                    job.peakBytes.empty() ? largestPeakBytes
                                          : static_cast<std::size_t>(job.peakBytes.back());
                warmFreeMemory(previousPeak + kWarmMarginBytes);
            }
            probe.start();
            const Stopwatch stopwatch;
            if (!job.run()) {
                job.stopped = true;
                continue;
            }
            job.seconds.push_back(stopwatch.seconds());
            if (const std::optional<std::size_t> peak = probe.peakGrowthBytes()) {
                job.peakBytes.push_back(static_cast<double>(*peak));
                largestPeakBytes = std::max(largestPeakBytes, *peak);
            }
            job.afterRun();
            if (job.seconds.back() > job.limitSeconds)
                job.stopped = true;
        }
    }
}

} // namespace terratin::bench

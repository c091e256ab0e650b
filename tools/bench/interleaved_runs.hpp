#pragma once
// Timing several configurations on the same points in rounds, one run of each per round, so
// that the host's drift (on a shared virtual machine its speed changes by tens of percent
// from one minute to the next) falls on all of them alike and their ratios stay meaningful.

#include <cstddef>
#include <functional>
#include <limits>
#include <span>
#include <vector>

namespace terratin::bench {

/// One configuration to time: a terratin method or a peer.
struct TimedJob {
    /// The timed call. Returns false when it failed: nothing is recorded and the job stops.
    std::function<bool()> run;
    /// Reads and frees what the run made, untimed.
    std::function<void()> afterRun;
    /// A run longer than this is the job's last (a peer too slow to repeat).
    double limitSeconds = std::numeric_limits<double>::infinity();

    /// Wall-clock seconds and peak resident growth (when measurable) of each run.
    std::vector<double> seconds;
    std::vector<double> peakBytes;
    bool stopped = false;
};

/// Runs every job once per round, in the order given, for `rounds` rounds (fewer for a job
/// that fails or overruns its limit). With `warmMemory`, each run is preceded, untimed, by
/// warmFreeMemory of what that job's previous run used at its peak (the largest peak of
/// any run so far for a job's first run), plus a margin.
void runInterleaved(std::span<TimedJob> jobs, unsigned rounds, bool warmMemory);

} // namespace terratin::bench

#pragma once
// How much faster the machine runs independent work on several threads than on one: the
// ceiling of every parallel speed-up measured beside it. On a virtual machine two "cores"
// may be one physical core's two hyperthreads, or share it with other guests, and then no
// parallel code gets near twice the speed.

#include <cstdio>
#include <span>

namespace terratin::bench {

struct HostScaling {
    /// Speed-up of a chain of dependent floating-point operations per thread.
    double compute = 0.0;
    /// Speed-up of a chase of random pointers through an array per thread, larger than the
    /// caches of a core (latency-bound, like point location in a large triangulation).
    double memory = 0.0;
};

/// threads x time on one thread / time on all threads, for each round's pair of timings (the
/// same work per thread in both), and the median of those: 1 when the threads gain nothing,
/// `threads` when they scale perfectly.
[[nodiscard]] double medianSpeedUp(std::span<const double> secondsOnOne,
                                   std::span<const double> secondsOnAll, unsigned threads);

/// Runs both kinds of work on 1 and on `threads` threads, alternating, `rounds` times (about
/// a second in all).
[[nodiscard]] HostScaling measureHostScaling(unsigned threads, int rounds);

/// Measures and prints, as a comment line of the benchmark tables, how the host scales to
/// `threads` threads (nothing for one thread).
void printHostScaling(std::FILE* out, unsigned threads);

} // namespace terratin::bench

#include "host_scaling.hpp"

#include <algorithm>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <thread>
#include <vector>

namespace terratin::bench {

namespace {

// Work per thread: enough of each kind to dwarf starting the threads (what it took on one
// machine: docs/benchmarks.md).
constexpr std::size_t kComputeSteps = std::size_t{40} << 20U;
constexpr std::size_t kChaseSteps = std::size_t{1} << 20U;
// 64 MiB per thread: beyond a core's L2, and with two threads most of a shared L3.
constexpr std::size_t kChaseEntries = std::size_t{16} << 20U;

double dependentArithmetic(std::size_t steps) {
    double x = 1.0;
    for (std::size_t i = 0; i < steps; ++i)
        x = x * 1.0000001 + 1e-9;
    return x;
}

std::uint32_t chase(const std::vector<std::uint32_t>& next, std::size_t steps) {
    std::uint32_t at = 0;
    for (std::size_t i = 0; i < steps; ++i)
        at = next[at];
    return at;
}

// One random cycle through all entries (Sattolo's algorithm), so a chase never settles into
// a short loop that fits in cache.
std::vector<std::uint32_t> randomCycle(std::size_t entries, std::uint64_t seed) {
    std::vector<std::uint32_t> next(entries);
    for (std::size_t i = 0; i < entries; ++i)
        next[i] = static_cast<std::uint32_t>(i);
    std::uint64_t state = seed;
    for (std::size_t i = entries - 1; i > 0; --i) {
        state = state * 6364136223846793005ULL + 1442695040888963407ULL;
        const std::size_t j = (state >> 33U) % i;
        std::swap(next[i], next[j]);
    }
    return next;
}

// Seconds for `threads` threads to run work(thread) each.
template <class Work> double timeOnThreads(unsigned threads, Work&& work) {
    const auto start = std::chrono::steady_clock::now();
    std::vector<std::jthread> running;
    for (unsigned t = 0; t < threads; ++t)
        running.emplace_back([&work, t] { work(t); });
    running.clear(); // joins
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

} // namespace

double medianSpeedUp(std::span<const double> secondsOnOne, std::span<const double> secondsOnAll,
                     unsigned threads) {
    std::vector<double> speedUps;
    for (std::size_t r = 0; r < std::min(secondsOnOne.size(), secondsOnAll.size()); ++r)
        speedUps.push_back(threads * secondsOnOne[r] / secondsOnAll[r]);
    if (speedUps.empty())
        return 0.0;
    std::sort(speedUps.begin(), speedUps.end());
    const std::size_t middle = speedUps.size() / 2;
    return speedUps.size() % 2 == 1 ? speedUps[middle]
                                    : (speedUps[middle - 1] + speedUps[middle]) / 2.0;
}

HostScaling measureHostScaling(unsigned threads, int rounds) {
    threads = std::max(1U, threads);
    std::vector<std::vector<std::uint32_t>> cycles;
    for (unsigned t = 0; t < threads; ++t)
        cycles.push_back(randomCycle(kChaseEntries, t + 1));
    // Results land here so that the compiler cannot drop the work.
    std::vector<double> sink(threads);
    const auto compute = [&](unsigned t) { sink[t] = dependentArithmetic(kComputeSteps); };
    const auto memory = [&](unsigned t) { sink[t] = chase(cycles[t], kChaseSteps); };
    std::vector<double> computeOne;
    std::vector<double> computeAll;
    std::vector<double> memoryOne;
    std::vector<double> memoryAll;
    for (int r = 0; r < rounds; ++r) {
        computeOne.push_back(timeOnThreads(1, compute));
        computeAll.push_back(timeOnThreads(threads, compute));
        memoryOne.push_back(timeOnThreads(1, memory));
        memoryAll.push_back(timeOnThreads(threads, memory));
    }
    return {medianSpeedUp(computeOne, computeAll, threads),
            medianSpeedUp(memoryOne, memoryAll, threads)};
}

void printHostScaling(std::FILE* out, unsigned threads) {
    if (threads < 2)
        return;
    constexpr int kRounds = 5;
    const HostScaling scaling = measureHostScaling(threads, kRounds);
    std::fprintf(out,
                 "# host scaling: independent work runs %.2fx (arithmetic) and %.2fx (memory "
                 "latency) as fast on %u threads as on 1: the ceiling of the speed-ups above\n",
                 scaling.compute, scaling.memory, threads);
}

} // namespace terratin::bench

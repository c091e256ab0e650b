#pragma once
/// @file
/// The data-parallel loops around the triangulation (keys for the insertion order, the
/// final extraction): contiguous blocks, one per thread, no pool. The loops are a few passes
/// over millions of elements, so starting threads costs microseconds against milliseconds.

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace terratin::detail {

/// Below this many elements a loop runs on the calling thread alone.
inline constexpr std::size_t kParallelForMinimum = std::size_t{1} << 16;

/// `threads`, or every hardware thread for 0.
inline unsigned threadsOrAll(unsigned threads) {
    return threads != 0 ? threads : std::max(1U, std::thread::hardware_concurrency());
}

/// The threads parallelFor uses for `count` elements when allowed `threads`.
inline unsigned parallelForThreads(std::size_t count, unsigned threads) {
    if (count < kParallelForMinimum)
        return 1;
    return static_cast<unsigned>(
        std::clamp<std::size_t>(threads, 1, count / (kParallelForMinimum / 2)));
}

/// Calls body(index) for every index of [0, count), each on a thread of its own (index 0 on
/// the calling thread). Rethrows the first exception after every thread has finished.
template <class Body> void runOnThreads(unsigned count, Body&& body) {
    std::mutex failureMutex;
    std::exception_ptr failure;
    const auto run = [&](unsigned index) {
        try {
            body(index);
        } catch (...) {
            const std::lock_guard lock(failureMutex);
            if (!failure)
                failure = std::current_exception();
        }
    };
    {
        std::vector<std::jthread> others;
        others.reserve(count - 1);
        for (unsigned index = 1; index < count; ++index)
            others.emplace_back(run, index);
        run(0);
    }
    if (failure)
        std::rethrow_exception(failure);
}

/// Calls body(block, begin, end) for the blocks of [0, count) split into
/// parallelForThreads(count, threads) contiguous ranges, block 0 on the calling thread.
/// Rethrows the first exception after every thread has finished.
template <class Body> void parallelFor(std::size_t count, unsigned threads, Body&& body) {
    const unsigned blocks = parallelForThreads(count, threads);
    const auto begin = [&](unsigned block) { return count * block / blocks; };
    if (blocks == 1) {
        body(0U, std::size_t{0}, count);
        return;
    }
    runOnThreads(blocks, [&](unsigned block) { body(block, begin(block), begin(block + 1)); });
}

/// Like parallelFor, but the threads take chunks of `chunk` elements in turn, for loops whose
/// elements cost unevenly (a large triangle holds many cells, a small one few): body(block,
/// begin, end) is called for each chunk, `block` naming the thread (0 to
/// parallelForThreads(count, threads) - 1), so per-thread results need no lock.
template <class Body>
void parallelForChunks(std::size_t count, unsigned threads, std::size_t chunk, Body&& body) {
    std::atomic<std::size_t> next{0};
    parallelFor(count, threads, [&](unsigned block, std::size_t, std::size_t) {
        for (std::size_t begin = next.fetch_add(chunk); begin < count;
             begin = next.fetch_add(chunk))
            body(block, begin, std::min(count, begin + chunk));
    });
}

/// Calls body(begin, end) for the chunks of `chunk` elements of [0, count) on up to `threads`
/// threads (0: all hardware threads; at most one per chunk), which take the chunks in turn: for
/// a few elements that each cost much and unevenly (polylines), which parallelForChunks would
/// leave on one thread.
template <class Body>
void forChunksInTurn(std::size_t count, unsigned threads, std::size_t chunk, Body&& body) {
    const std::size_t chunks = (count + chunk - 1) / chunk;
    std::atomic<std::size_t> next{0};
    runOnThreads(static_cast<unsigned>(std::clamp<std::size_t>(chunks, 1, threadsOrAll(threads))),
                 [&](unsigned) {
                     for (std::size_t k = next++; k < chunks; k = next++)
                         body(k * chunk, std::min(count, (k + 1) * chunk));
                 });
}

} // namespace terratin::detail

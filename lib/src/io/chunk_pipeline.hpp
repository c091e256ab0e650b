#pragma once
/// @file
/// Two-stage pipeline over chunks: chunk k + 1 is prepared on another thread while chunk k is
/// consumed on the calling thread. The vector writers use it where the consumer (SQLite, an
/// OGR driver) is single-threaded and the preparation (attributes, geometry blobs) can run
/// beside it.

#include <array>
#include <cstddef>
#include <future>

#include <tbb/task_arena.h>

namespace terratin::io::detail {

/// Calls prepare(k, buffer) and then consume(k, buffer) for k = 0 .. chunks - 1, preparing the
/// next chunk while the current one is consumed. An exception from either stops the pipeline
/// (after the preparation in flight has finished) and propagates.
template <class Buffer, class Prepare, class Consume>
void runChunkPipeline(std::size_t chunks, Prepare&& prepare, Consume&& consume) {
    if (chunks == 0)
        return;
    // The future is declared after the buffers so that it is waited for before they go away.
    std::array<Buffer, 2> buffers;
    std::future<void> next;
    prepare(std::size_t{0}, buffers[0]);
    for (std::size_t k = 0; k < chunks; ++k) {
        if (k + 1 < chunks)
            next = std::async(std::launch::async, [&, k] { prepare(k + 1, buffers[(k + 1) % 2]); });
        consume(k, buffers[k % 2]);
        if (next.valid())
            next.get();
    }
}

/// runChunkPipeline with the preparation kept on one thread. The consumer is the slower stage
/// by far, so preparing on more threads (attributes are otherwise computed with TBB on every
/// core) would only take cores from it.
template <class Buffer, class Prepare, class Consume>
void runBesideOneWriter(std::size_t chunks, Prepare&& prepare, Consume&& consume) {
    tbb::task_arena oneThread(1);
    runChunkPipeline<Buffer>(
        chunks,
        [&](std::size_t k, Buffer& buffer) { oneThread.execute([&] { prepare(k, buffer); }); },
        consume);
}

} // namespace terratin::io::detail

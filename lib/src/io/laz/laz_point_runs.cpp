/// @file
/// The rounds of decodeChunksInOrder (see laz_point_runs.hpp).

#include "laz_point_runs.hpp"

#include "../../parallel/parallel_for.hpp"

#include <algorithm>
#include <atomic>
#include <exception>
#include <vector>

namespace terratin::io::laz {

namespace {

/// Chunks per round and worker: enough that a round's last, partial chunk leaves the other
/// workers idle only briefly, few enough that a round's results stay small.
constexpr std::size_t kChunksPerWorker = 4;

/// One worker's decoder and buffers, kept from round to round.
struct Worker {
    ChunkDecoder decoder;
    std::vector<std::byte> compressed;
    std::vector<std::byte> records;
};

void decodeChunk(const LazFile& file, std::size_t index, std::size_t recordsPerPiece,
                 Worker& worker,
                 const std::function<void(std::size_t, std::span<const std::byte>)>& decodeRun) {
    const LazChunk& chunk = file.chunks()[index];
    file.readChunk(index, worker.compressed);
    worker.decoder.begin(worker.compressed, chunk.pointCount, file.chunkLabel(index));
    const std::size_t length = worker.decoder.recordLength();
    while (worker.decoder.pointsLeft() > 0) {
        const auto count = static_cast<std::size_t>(
            std::min<std::uint64_t>(recordsPerPiece, worker.decoder.pointsLeft()));
        worker.records.resize(count * length);
        worker.decoder.decodeNext(worker.records);
        decodeRun(index, worker.records);
    }
}

} // namespace

bool decodeChunksInOrder(
    const LazFile& file, const ChunkRunOptions& options,
    const std::function<void(std::size_t, std::span<const std::byte>)>& decodeRun,
    const std::function<bool(std::size_t)>& takeRun) {
    const std::size_t chunkCount = file.chunks().size();
    const auto workerCount = static_cast<unsigned>(std::clamp<std::size_t>(
        terratin::detail::threadsOrAll(options.threads), 1, std::max<std::size_t>(1, chunkCount)));
    std::vector<Worker> workers;
    workers.reserve(workerCount);
    for (unsigned w = 0; w < workerCount; ++w)
        workers.push_back({ChunkDecoder(file.laszip(), file.name(), options.fields), {}, {}});
    const std::size_t recordsPerPiece = std::max<std::size_t>(1, options.recordsPerPiece);
    const std::size_t roundSize = workerCount * kChunksPerWorker;
    for (std::size_t first = 0; first < chunkCount; first += roundSize) {
        const std::size_t end = std::min(chunkCount, first + roundSize);
        // Each chunk's failure is kept, and the first chunk's in file order is the one
        // reported, so a damaged file gives the same error on any number of threads.
        std::vector<std::exception_ptr> failures(end - first);
        std::atomic<std::size_t> next{first};
        terratin::detail::runOnThreads(workerCount, [&](unsigned w) {
            for (std::size_t i = next++; i < end; i = next++) {
                try {
                    decodeChunk(file, i, recordsPerPiece, workers[w], decodeRun);
                } catch (...) {
                    failures[i - first] = std::current_exception();
                }
            }
        });
        for (std::size_t i = first; i < end; ++i) {
            if (failures[i - first])
                std::rethrow_exception(failures[i - first]);
            if (!takeRun(i))
                return false;
        }
    }
    return true;
}

} // namespace terratin::io::laz

#pragma once
/// @file
/// Every point of a LAZ file decoded on several threads in bounded memory, handed on in file
/// order. Chunks are independent, so a round of chunks decodes at once, one worker per
/// chunk; each worker turns its chunk's records into the caller's results (the points a TIN
/// keeps, say) piece by piece, and the calling thread then takes the results in chunk order.
/// Memory: one piece of records per worker, plus the results of one round.

#include "chunk_decoder.hpp"
#include "laz_file.hpp"

#include <cstddef>
#include <cstdint>
#include <functional>
#include <span>

namespace terratin::io::laz {

/// How the chunks of a file are decoded.
struct ChunkRunOptions {
    FieldSelection fields = FieldSelection::Every;
    /// Worker threads; 0: every hardware thread.
    unsigned threads = 0;
    /// Records decoded at a time within a chunk: bounds the records buffer of each worker
    /// whatever a chunk claims to hold.
    std::size_t recordsPerPiece = std::size_t{1} << 14;
};

/// Decodes every chunk of `file`. For chunk i, on a worker thread, `decodeRun(i, records)` is
/// called with each piece of its decoded records (whole records, in order; several calls per
/// chunk); once a round's chunks are done, `takeRun(i)` is called on the calling thread for
/// each of them in chunk order, and may return false to stop (cancellation: nothing more is
/// decoded). A worker's decodeRun calls for one chunk come from one thread, but different
/// chunks decode at once, so decodeRun must keep each chunk's results apart.
/// Throws the error of the first failing chunk in file order (InvalidInputError for a corrupt
/// one), once the round's workers have stopped; returns whether every chunk was taken.
bool decodeChunksInOrder(
    const LazFile& file, const ChunkRunOptions& options,
    const std::function<void(std::size_t, std::span<const std::byte>)>& decodeRun,
    const std::function<bool(std::size_t)>& takeRun);

} // namespace terratin::io::laz

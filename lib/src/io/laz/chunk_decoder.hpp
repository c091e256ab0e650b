#pragma once
/// @file
/// Decoding of one chunk of LAZ point data to raw LAS point records. A chunk starts with its
/// first point stored raw (the record bytes, item after item); in the pointwise compressors (1,
/// 2) one arithmetic-coded stream then carries the other points, in the layered one (3, LAS 1.4
/// point formats 6-10) one stream per field group (layered_chunk.hpp). Every model starts
/// afresh in each chunk, so chunks decode independently of each other, on any thread, into a
/// buffer of the caller's. The unchunked compressor (1) is one chunk holding every point.

#include "laszip_vlr.hpp"

#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <string_view>

namespace terratin::io::laz {

/// Which fields of each record a decoder must fill. The layered compressor (3) stores each
/// field group in its own stream, so a reader that needs only what a TIN is built from skips
/// the others at no cost; the pointwise compressors decode every field whatever is asked.
enum class FieldSelection {
    Every,
    /// x, y, z, return number, number of returns, classification and the classification
    /// flags (withheld); every other byte of a record is left as in the chunk's first record.
    TinFields,
};

class ChunkDecoder {
public:
    /// A decoder for the point records `record` describes, decoding `fields` of them (the
    /// layered compressor alone can skip fields; see FieldSelection). Throws InvalidInputError
    /// naming `fileName` when they need what this decoder does not do: items stored
    /// uncompressed within a compressed file (version 0), the version 4 items of LAS 1.5, LAS
    /// 1.4 items under a pointwise compressor or LAS 1.0-1.3 items under the layered one.
    ChunkDecoder(const LaszipRecord& record, std::string_view fileName,
                 FieldSelection fields = FieldSelection::Every);
    ~ChunkDecoder();
    ChunkDecoder(ChunkDecoder&&) noexcept;
    ChunkDecoder& operator=(ChunkDecoder&&) noexcept;
    ChunkDecoder(const ChunkDecoder&) = delete;
    ChunkDecoder& operator=(const ChunkDecoder&) = delete;

    /// Bytes of one point record: the items' sizes added.
    [[nodiscard]] std::size_t recordLength() const;

    /// Starts on a chunk of `pointCount` points held in `chunk` (which must stay alive until
    /// the chunk is done). `label` names it in errors ("chunk 3 of 11").
    void begin(std::span<const std::byte> chunk, std::uint64_t pointCount, std::string label);
    /// The next records.size() / recordLength() points of the chunk, as LAS records.
    /// Throws InvalidInputError when the chunk turns out truncated or corrupt;
    /// std::invalid_argument when more points are asked for than it has left, or for a
    /// buffer that is not a whole number of records.
    void decodeNext(std::span<std::byte> records);
    /// Points of the current chunk not decoded yet.
    [[nodiscard]] std::uint64_t pointsLeft() const;
    /// Bytes of the chunk used so far: once every point is decoded, the chunk's compressed
    /// size (a writer's encoder ends its stream exactly where the decoder stops reading).
    [[nodiscard]] std::size_t bytesUsed() const;

    /// The whole chunk at once: begin, then every point into `records` (pointCount x
    /// recordLength bytes). Returns bytesUsed().
    std::size_t decode(std::span<const std::byte> chunk, std::uint64_t pointCount,
                       std::span<std::byte> records, std::string label);

private:
    struct State;
    std::unique_ptr<State> m_state;
};

} // namespace terratin::io::laz

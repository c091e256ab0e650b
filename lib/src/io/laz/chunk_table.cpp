/// @file
/// Finding the chunks of a LAZ file (see chunk_table.hpp). A writer that could not seek back
/// (a stream) leaves -1 as the table pointer and appends the table's position as the file's
/// last 8 bytes; one interrupted before writing the table leaves the pointer pointing at
/// itself. The table can then be rebuilt: a layered chunk states its own size and point count;
/// a pointwise chunk of a fixed size is decoded, its coded stream ending exactly where the
/// next chunk starts.

#include "chunk_table.hpp"

#include "chunk_decoder.hpp"
#include "integer_decoder.hpp"
#include "layered_chunk.hpp"
#include "laz_bytes.hpp"
#include "laz_error.hpp"
#include "range_decoder.hpp"

#include <algorithm>
#include <array>

namespace terratin::io::laz {

namespace {

constexpr std::uint64_t kPointerBytes = 8;
/// Table header: u32 version, u32 chunk count.
constexpr std::uint64_t kTableHeaderBytes = 8;
/// More than any coded entry can take: two 32-bit values of at most 33 magnitude classes,
/// 8 coded and 24 raw bits each, with room to spare.
constexpr std::uint64_t kMostBytesPerEntry = 24;

/// The end of the bytes that can hold points: the first EVLR when it follows them (LAS 1.4),
/// else the end of the file.
std::uint64_t pointDataEnd(const detail::ByteSource& source, const LasHeader& h) {
    if (h.evlrCount > 0 && h.evlrStart >= h.pointDataOffset && h.evlrStart <= source.size())
        return h.evlrStart;
    return source.size();
}

std::uint64_t fixedChunkCount(std::uint64_t points, std::uint32_t chunkSize) {
    return points / chunkSize + (points % chunkSize != 0 ? 1 : 0);
}

ChunkList unchunked(const detail::ByteSource& source, const LasHeader& h) {
    ChunkList list;
    if (h.pointCount > 0)
        list.chunks.push_back(
            {h.pointDataOffset, pointDataEnd(source, h) - h.pointDataOffset, 0, h.pointCount});
    return list;
}

/// Chunk byte ranges and point counts from decoded table entries, checked.
std::vector<LazChunk> chunksFromEntries(const std::vector<ChunkTableEntry>& entries,
                                        std::string_view name, const LasHeader& h,
                                        const LaszipRecord& laszip, std::uint64_t tableStart) {
    std::vector<LazChunk> chunks;
    chunks.reserve(entries.size());
    std::uint64_t offset = h.pointDataOffset + kPointerBytes;
    std::uint64_t firstPoint = 0;
    for (std::size_t i = 0; i < entries.size(); ++i) {
        const std::string which =
            "chunk " + std::to_string(i + 1) + " of " + std::to_string(entries.size());
        const ChunkTableEntry& entry = entries[i];
        if (entry.byteCount == 0 || offset + entry.byteCount > tableStart)
            throwInvalidLaz(name, "the chunk table is corrupt: " + which + " has " +
                                      std::to_string(entry.byteCount) + " bytes from byte " +
                                      std::to_string(offset) +
                                      ", outside the point data (which "
                                      "end at the table, byte " +
                                      std::to_string(tableStart) + ")");
        const std::uint64_t points =
            laszip.variableChunks()
                ? entry.pointCount
                : std::min<std::uint64_t>(laszip.chunkSize, h.pointCount - firstPoint);
        chunks.push_back({offset, entry.byteCount, firstPoint, points});
        offset += entry.byteCount;
        firstPoint += points;
    }
    if (firstPoint != h.pointCount)
        throwInvalidLaz(name, "the chunk table's " + std::to_string(entries.size()) +
                                  " chunks hold " + std::to_string(firstPoint) +
                                  " points, but the header declares " +
                                  std::to_string(h.pointCount));
    return chunks;
}

/// The table at `tableStart`, checked against the header and the file.
std::vector<LazChunk> readTable(const detail::ByteSource& source, std::string_view name,
                                const LasHeader& h, const LaszipRecord& laszip,
                                std::uint64_t tableStart) {
    const std::uint64_t chunksStart = h.pointDataOffset + kPointerBytes;
    const std::uint64_t fileSize = source.size();
    if (tableStart < chunksStart || tableStart > fileSize ||
        fileSize - tableStart < kTableHeaderBytes)
        throwInvalidLaz(name, "the chunk table pointer " + std::to_string(tableStart) +
                                  " lies outside the " + std::to_string(fileSize) +
                                  "-byte file's room for a table after the point data starting "
                                  "at byte " +
                                  std::to_string(chunksStart) + " (truncated?)");
    std::array<std::byte, kTableHeaderBytes> head{};
    source.read(tableStart, head);
    ByteCursor cursor(head);
    const auto version = cursor.read<std::uint32_t>();
    const auto count = cursor.read<std::uint32_t>();
    if (version != 0)
        throwInvalidLaz(name, "chunk table version " + std::to_string(version) +
                                  " is unknown (LASzip writes version 0)");
    if (!laszip.variableChunks() && count != fixedChunkCount(h.pointCount, laszip.chunkSize))
        throwInvalidLaz(name, "the chunk table lists " + std::to_string(count) + " chunks, but " +
                                  std::to_string(h.pointCount) + " points in chunks of " +
                                  std::to_string(laszip.chunkSize) + " make " +
                                  std::to_string(fixedChunkCount(h.pointCount, laszip.chunkSize)));
    // Every chunk holds at least its raw first point, which bounds the count by the bytes.
    if (std::uint64_t{count} * h.recordLength > tableStart - chunksStart)
        throwInvalidLaz(
            name, "the chunk table lists " + std::to_string(count) + " chunks, more than the " +
                      std::to_string(tableStart - chunksStart) + " bytes of point data can hold");
    const std::uint64_t codedStart = tableStart + kTableHeaderBytes;
    const std::uint64_t codedBytes =
        std::min(fileSize - codedStart, count * kMostBytesPerEntry + kMostBytesPerEntry);
    std::vector<std::byte> coded(static_cast<std::size_t>(codedBytes));
    source.read(codedStart, coded);
    const std::vector<ChunkTableEntry> entries =
        decodeChunkTableEntries(coded, count, laszip.variableChunks(), name);
    return chunksFromEntries(entries, name, h, laszip, tableStart);
}

/// Decodes one chunk of `points` points from `offset`, reading more of the file only when
/// the first guess of its size falls short; returns its compressed size.
std::uint64_t measureChunk(const detail::ByteSource& source, ChunkDecoder& decoder,
                           std::uint64_t offset, std::uint64_t end, std::uint64_t points,
                           std::string label, std::vector<std::byte>& bytes,
                           std::vector<std::byte>& records) {
    const std::uint64_t raw = points * decoder.recordLength();
    const std::array<std::uint64_t, 2> guesses{raw + raw / 2 + 4096, 4 * raw + 65536};
    for (std::size_t attempt = 0; attempt < guesses.size(); ++attempt) {
        const std::uint64_t window = std::min(end - offset, guesses[attempt]);
        bytes.resize(static_cast<std::size_t>(window));
        source.read(offset, bytes);
        records.resize(static_cast<std::size_t>(raw));
        try {
            return decoder.decode(bytes, points, records, label);
        } catch (const InvalidInputError&) {
            if (window == end - offset || attempt + 1 == guesses.size())
                throw;
        }
    }
    return 0; // not reached: the last attempt returns or throws
}

/// The chunk list of a layered file whose table is missing, from the chunks' own layouts: a
/// layered chunk states its point count and the sizes of its layers after its first record
/// (layered_chunk.hpp), so nothing needs decoding, and variable chunks are found too.
std::vector<LazChunk> rebuildLayeredTable(const detail::ByteSource& source, std::string_view name,
                                          const LasHeader& h, const LaszipRecord& laszip,
                                          const std::string& why) {
    const LayeredChunkDecoder layout(laszip, name, FieldSelection::TinFields);
    const std::uint64_t end = pointDataEnd(source, h);
    std::vector<std::byte> head(h.recordLength + 4 + 4 * layout.layerCount());
    std::vector<LazChunk> chunks;
    std::uint64_t offset = h.pointDataOffset + kPointerBytes;
    for (std::uint64_t first = 0; first < h.pointCount;) {
        const std::string which = "chunk " + std::to_string(chunks.size() + 1);
        if (end < offset || end - offset < head.size())
            throwInvalidLaz(name, why +
                                      "; rebuilding it from the chunks' layouts ran out of "
                                      "point data at " +
                                      which + ", after " + std::to_string(first) + " of " +
                                      std::to_string(h.pointCount) + " points");
        source.read(offset, head);
        const auto points = loadLe<std::uint32_t>(head.data() + h.recordLength);
        std::uint64_t bytes = head.size();
        for (std::size_t layer = 0; layer < layout.layerCount(); ++layer)
            bytes += loadLe<std::uint32_t>(head.data() + h.recordLength + 4 + 4 * layer);
        if (points == 0 || points > h.pointCount - first || bytes > end - offset)
            throwInvalidLaz(name, why + "; " + which + " found without it states " +
                                      std::to_string(points) + " points in " +
                                      std::to_string(bytes) +
                                      " bytes, which do not fit the header's count or the file");
        chunks.push_back({offset, bytes, first, points});
        offset += bytes;
        first += points;
    }
    return chunks;
}

/// The chunk list of a file whose table is missing, found by decoding chunk after chunk.
std::vector<LazChunk> rebuildTable(const detail::ByteSource& source, std::string_view name,
                                   const LasHeader& h, const LaszipRecord& laszip,
                                   const std::string& why) {
    if (laszip.compressor == Compressor::LayeredChunked)
        return rebuildLayeredTable(source, name, h, laszip, why);
    if (laszip.variableChunks())
        throwInvalidLaz(name, why + ", and its chunks have variable point counts, which only "
                                    "the table records: the chunks cannot be found without it");
    ChunkDecoder decoder(laszip, name);
    const std::uint64_t end = pointDataEnd(source, h);
    std::vector<LazChunk> chunks;
    std::vector<std::byte> bytes;
    std::vector<std::byte> records;
    std::uint64_t offset = h.pointDataOffset + kPointerBytes;
    for (std::uint64_t first = 0; first < h.pointCount;) {
        if (offset >= end)
            throwInvalidLaz(name, why + "; rebuilding it by decoding ran out of point data after " +
                                      std::to_string(first) + " of " +
                                      std::to_string(h.pointCount) + " points");
        const std::uint64_t points =
            std::min<std::uint64_t>(laszip.chunkSize, h.pointCount - first);
        const std::string label =
            "chunk " + std::to_string(chunks.size() + 1) + " (found without a chunk table)";
        const std::uint64_t used =
            measureChunk(source, decoder, offset, end, points, label, bytes, records);
        chunks.push_back({offset, used, first, points});
        offset += used;
        first += points;
    }
    return chunks;
}

ChunkList chunked(const detail::ByteSource& source, std::string_view name, const LasHeader& h,
                  const LaszipRecord& laszip) {
    const std::uint64_t pointerAt = h.pointDataOffset;
    if (source.size() - pointerAt < kPointerBytes)
        throwInvalidLaz(name, "truncated: no room for the 8-byte chunk table pointer at the point "
                              "data (byte " +
                                  std::to_string(pointerAt) + ")");
    std::array<std::byte, kPointerBytes> pointer{};
    source.read(pointerAt, pointer);
    const auto tableStart = loadLe<std::int64_t>(pointer.data());
    ChunkList list;
    if (tableStart == static_cast<std::int64_t>(pointerAt)) {
        list.chunks = rebuildTable(source, name, h, laszip,
                                   "the chunk table is missing (its pointer points at itself: "
                                   "the writer was interrupted)");
        list.origin = ChunkListOrigin::Rebuilt;
    } else if (tableStart == -1) {
        // A streaming writer's table: its position is the file's last 8 bytes.
        std::array<std::byte, kPointerBytes> trailing{};
        source.read(source.size() - kPointerBytes, trailing);
        try {
            list.chunks =
                readTable(source, name, h, laszip, loadLe<std::uint64_t>(trailing.data()));
            list.origin = ChunkListOrigin::TrailingPointer;
        } catch (const InvalidInputError&) {
            list.chunks = rebuildTable(source, name, h, laszip,
                                       "the chunk table is missing (pointer -1 from a streaming "
                                       "writer, and no table where the file's last 8 bytes "
                                       "point)");
            list.origin = ChunkListOrigin::Rebuilt;
        }
    } else {
        list.chunks = readTable(source, name, h, laszip, static_cast<std::uint64_t>(tableStart));
        list.origin = ChunkListOrigin::Table;
    }
    return list;
}

} // namespace

std::vector<ChunkTableEntry> decodeChunkTableEntries(std::span<const std::byte> coded,
                                                     std::uint32_t count, bool variableChunks,
                                                     std::string_view fileName) {
    std::vector<ChunkTableEntry> entries(count);
    if (count == 0)
        return entries;
    RangeDecoder decoder;
    decoder.start(coded.data(), coded.data() + coded.size());
    IntegerDecoder values(32, 2);
    ChunkTableEntry previous;
    for (ChunkTableEntry& entry : entries) {
        if (variableChunks)
            entry.pointCount = static_cast<std::uint32_t>(
                values.decode(decoder, static_cast<std::int32_t>(previous.pointCount), 0));
        entry.byteCount = static_cast<std::uint32_t>(
            values.decode(decoder, static_cast<std::int32_t>(previous.byteCount), 1));
        previous = entry;
    }
    if (decoder.overran() || decoder.corrupt())
        throwInvalidLaz(fileName, "the chunk table is truncated or corrupt: its " +
                                      std::to_string(count) + " entries do not decode from the " +
                                      std::to_string(coded.size()) + " bytes after it");
    return entries;
}

ChunkList locateChunks(const detail::ByteSource& source, std::string_view fileName,
                       const LasHeader& header, const LaszipRecord& laszip) {
    if (!laszip.chunked())
        return unchunked(source, header);
    return chunked(source, fileName, header, laszip);
}

} // namespace terratin::io::laz

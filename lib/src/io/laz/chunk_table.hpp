#pragma once
/// @file
/// The chunks of a LAZ file: found through the chunk table that chunked compressors write
/// after the points (layout in laz_file.hpp), or by decoding when a writer never finished the
/// table. The unchunked compressors give one chunk of every point.

#include "laszip_vlr.hpp"
#include "laz_file.hpp"

#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

namespace terratin::io::laz {

/// One entry of the chunk table, as coded: a chunk's point count (variable chunks only; 0
/// otherwise) and its compressed size in bytes.
struct ChunkTableEntry {
    std::uint32_t pointCount = 0;
    std::uint32_t byteCount = 0;
};

/// Decodes `count` entries from the arithmetic-coded part of a chunk table (the bytes after
/// its version and count). Each value is predicted from the previous entry's, through one
/// 32-bit integer decoder with a context for point counts (0) and one for sizes (1).
/// Throws InvalidInputError naming `fileName` when `coded` ends too soon or is corrupt.
[[nodiscard]] std::vector<ChunkTableEntry> decodeChunkTableEntries(std::span<const std::byte> coded,
                                                                   std::uint32_t count,
                                                                   bool variableChunks,
                                                                   std::string_view fileName);

struct ChunkList {
    std::vector<LazChunk> chunks;
    ChunkListOrigin origin = ChunkListOrigin::NotChunked;
};

/// The chunks of the file whose header and LASzip VLR are given, checked against the point
/// count and the file size. Throws InvalidInputError naming `fileName` when they cannot be
/// found or disagree with the header.
[[nodiscard]] ChunkList locateChunks(const detail::ByteSource& source, std::string_view fileName,
                                     const LasHeader& header, const LaszipRecord& laszip);

} // namespace terratin::io::laz

#pragma once
/// @file
/// LazFile: the layout of a LAZ file (LASzip-compressed LAS), read without decoding any
/// point: the LAS header fields that place the points, the LASzip VLR, and the chunks with
/// their byte ranges and point counts. With ChunkDecoder this is the whole decoder:
///
///     LazFile file = LazFile::open(path);
///     ChunkDecoder decoder(file.laszip(), file.name());   // one per thread
///     for (std::size_t i = 0; i < file.chunks().size(); ++i) {
///         file.readChunk(i, bytes);
///         decoder.decode(bytes, file.chunks()[i].pointCount, records, file.chunkLabel(i));
///     }
///
/// The header and the VLRs are read and checked as in a LAS file (las_header.hpp).
/// Layout (LAS 1.4 R15 2.4 for the header; LASzip for the rest): the point data start at
/// the header's offset to point data, whatever lies between the last VLR and there. The
/// unchunked compressor (1) stores the points right there. The chunked ones (2, 3) store
/// first an int64 pointing to the chunk table, then the chunks back to back; the table holds
/// a u32 version (0), a u32 chunk count and, arithmetic-coded, each chunk's compressed size
/// (and, for variable chunks, its point count), each predicted from the previous chunk's.

#include "../byte_source.hpp"
#include "../las_header.hpp"
#include "laszip_vlr.hpp"

#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

namespace terratin::io::laz {

/// One independently decodable run of points.
struct LazChunk {
    std::uint64_t offset = 0;    ///< of its first byte in the file
    std::uint64_t byteCount = 0; ///< compressed size
    std::uint64_t firstPoint = 0;
    std::uint64_t pointCount = 0;
};

/// Where the chunk list came from.
enum class ChunkListOrigin {
    NotChunked,      ///< compressor 0 or 1: one chunk with every point (or none for 0 points)
    Table,           ///< the chunk table the pointer at the point data names
    TrailingPointer, ///< a streaming writer's table, found through the file's last 8 bytes
    Rebuilt,         ///< no table (the writer was interrupted): found by decoding every chunk
};

class LazFile {
public:
    /// Reads the layout of the LAZ file at `path`. Throws IoError when it cannot be read and
    /// InvalidInputError (one line naming the file and the fault) when it is not a LAZ file
    /// this decoder can place: no LASF signature, no LASzip VLR, a malformed LASzip VLR,
    /// items that do not add up to the record length, a chunk table that is missing, corrupt
    /// or disagrees with the point count, chunks outside the file.
    [[nodiscard]] static LazFile open(const std::string& path);
    /// The same, from bytes the caller keeps alive as long as the LazFile.
    [[nodiscard]] static LazFile fromMemory(std::span<const std::byte> bytes, std::string name);
    /// The LAZ file whose header (`parsed`, of a compressed file) was read from `source`,
    /// which the caller keeps alive as long as the LazFile.
    [[nodiscard]] static LazFile fromParsedHeader(const detail::ByteSource& source,
                                                  std::string name,
                                                  const detail::ParsedHeader& parsed);

    [[nodiscard]] const std::string& name() const { return m_name; }
    [[nodiscard]] const LasHeader& header() const { return m_header; }
    [[nodiscard]] const LaszipRecord& laszip() const { return m_laszip; }
    [[nodiscard]] const std::vector<LazChunk>& chunks() const { return m_chunks; }
    [[nodiscard]] ChunkListOrigin chunkListOrigin() const { return m_origin; }
    [[nodiscard]] std::uint64_t fileSize() const { return m_source->size(); }

    /// "chunk 3 of 11", for messages about chunk `index` (counted from 0).
    [[nodiscard]] std::string chunkLabel(std::size_t index) const;
    /// The compressed bytes of chunk `index` into `bytes` (resized). Safe to call from
    /// several threads at once.
    void readChunk(std::size_t index, std::vector<std::byte>& bytes) const;
    /// Any byte range of the file; `offset + out.size()` must not pass fileSize().
    void readBytes(std::uint64_t offset, std::span<std::byte> out) const;

private:
    LazFile(const detail::ByteSource& source, std::string name);
    void place(const detail::ParsedHeader& parsed);

    /// The source the LazFile opened itself (null when the caller's) and the one it reads.
    std::unique_ptr<detail::ByteSource> m_ownSource;
    const detail::ByteSource* m_source = nullptr;
    std::string m_name;
    LasHeader m_header;
    LaszipRecord m_laszip;
    std::vector<LazChunk> m_chunks;
    ChunkListOrigin m_origin = ChunkListOrigin::NotChunked;
};

} // namespace terratin::io::laz

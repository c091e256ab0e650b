/// @file
/// LazFile: the LAS header, the VLRs and the LASzip record of a LAZ file (see laz_file.hpp).
/// Only the header fields that place the points are read; every offset and length is checked
/// against the file size before anything is read at it.

#include "laz_file.hpp"

#include "chunk_table.hpp"
#include "laz_bytes.hpp"
#include "laz_error.hpp"

#include <array>
#include <cstring>
#include <stdexcept>

namespace terratin::io::laz {

namespace {

/// Bytes of the public header block: 1.0-1.2, 1.3 (waveform offset), 1.4 (EVLRs, 64-bit
/// counts) (LAS 1.4 R15, 2.4 table 3).
constexpr std::uint16_t kHeader12 = 227;
constexpr std::uint16_t kHeader13 = 235;
constexpr std::uint16_t kHeader14 = 375;
/// A VLR header: reserved u16, user id char[16], record id u16, length u16, text char[32].
constexpr std::uint64_t kVlrHeader = 54;

LazHeader parseHeader(const LazSource& source, std::string_view name) {
    const std::uint64_t fileSize = source.size();
    std::array<std::byte, kHeader14> raw{};
    if (fileSize >= 4)
        source.read(0, std::span(raw).first(4));
    if (fileSize < 4 || std::memcmp(raw.data(), "LASF", 4) != 0)
        throwInvalidLaz(name, "not a LAS or LAZ file (no LASF signature)");
    if (fileSize < kHeader12)
        throwInvalidLaz(name, "truncated: " + std::to_string(fileSize) +
                                  " bytes, shorter than a LAS header (227 bytes)");
    const std::size_t headerBytes = fileSize >= kHeader14 ? kHeader14 : kHeader12;
    source.read(0, std::span(raw).first(headerBytes));
    const std::byte* bytes = raw.data();

    LazHeader h;
    h.versionMajor = loadLe<std::uint8_t>(bytes + 24);
    h.versionMinor = loadLe<std::uint8_t>(bytes + 25);
    if (h.versionMajor != 1 || h.versionMinor > 4)
        throwInvalidLaz(name, "LAS version " + std::to_string(h.versionMajor) + "." +
                                  std::to_string(h.versionMinor) +
                                  " is not supported (1.0 to 1.4 are)");
    h.headerSize = loadLe<std::uint16_t>(bytes + 94);
    h.pointDataOffset = loadLe<std::uint32_t>(bytes + 96);
    h.vlrCount = loadLe<std::uint32_t>(bytes + 100);
    h.pointFormat = loadLe<std::uint8_t>(bytes + 104) & 0x3F;
    h.recordLength = loadLe<std::uint16_t>(bytes + 105);
    h.pointCount = loadLe<std::uint32_t>(bytes + 107);
    const std::uint16_t needed = h.versionMinor >= 4   ? kHeader14
                                 : h.versionMinor == 3 ? kHeader13
                                                       : kHeader12;
    if (h.headerSize < needed || h.headerSize > fileSize)
        throwInvalidLaz(name, "header size " + std::to_string(h.headerSize) +
                                  " does not fit a LAS 1." + std::to_string(h.versionMinor) +
                                  " header (at least " + std::to_string(needed) +
                                  " bytes) in a file of " + std::to_string(fileSize));
    if (h.versionMinor >= 4) {
        h.evlrOffset = loadLe<std::uint64_t>(bytes + 235);
        h.evlrCount = loadLe<std::uint32_t>(bytes + 243);
        if (const auto count64 = loadLe<std::uint64_t>(bytes + 247); count64 != 0)
            h.pointCount = count64;
    }
    if (h.pointFormat > 10)
        throwInvalidLaz(name, "point data record format " + std::to_string(h.pointFormat) +
                                  " is not supported (0 to 10 are)");
    if (h.pointDataOffset < h.headerSize || h.pointDataOffset > fileSize)
        throwInvalidLaz(name, "the point data offset " + std::to_string(h.pointDataOffset) +
                                  " lies outside the bytes after the " +
                                  std::to_string(h.headerSize) + "-byte header (file of " +
                                  std::to_string(fileSize) + " bytes)");
    return h;
}

/// The LASzip VLR among the VLRs between the header and the point data.
LaszipRecord findLaszipRecord(const LazSource& source, std::string_view name, const LazHeader& h) {
    std::uint64_t position = h.headerSize;
    for (std::uint32_t i = 0; i < h.vlrCount; ++i) {
        const std::string which =
            "variable length record " + std::to_string(i + 1) + " of " + std::to_string(h.vlrCount);
        if (position + kVlrHeader > h.pointDataOffset)
            throwInvalidLaz(name, which + " runs into the point data");
        std::array<std::byte, kVlrHeader> vlr{};
        source.read(position, vlr);
        ByteCursor cursor(vlr);
        cursor.skip(2);
        const std::string userId = cursor.readText(16);
        const auto recordId = cursor.read<std::uint16_t>();
        const auto length = cursor.read<std::uint16_t>();
        const std::uint64_t payload = position + kVlrHeader;
        if (payload + length > h.pointDataOffset)
            throwInvalidLaz(name, which + " runs into the point data");
        if (userId == kLaszipUserId && recordId == kLaszipRecordId) {
            std::vector<std::byte> bytes(length);
            source.read(payload, bytes);
            return parseLaszipRecord(bytes, name);
        }
        position = payload + length;
    }
    throwInvalidLaz(name, "no LASzip record (VLR 'laszip encoded' 22204) among its " +
                              std::to_string(h.vlrCount) +
                              " VLRs: not a LAZ file, or not compressed by LASzip");
}

} // namespace

LazFile::LazFile(std::unique_ptr<LazSource> source, std::string name)
    : m_source(std::move(source)), m_name(std::move(name)) {}

LazFile LazFile::open(const std::string& path) {
    LazFile file(openFileSource(path), path);
    file.parse();
    return file;
}

LazFile LazFile::fromMemory(std::span<const std::byte> bytes, std::string name) {
    LazFile file(memorySource(bytes), std::move(name));
    file.parse();
    return file;
}

void LazFile::parse() {
    m_header = parseHeader(*m_source, m_name);
    m_laszip = findLaszipRecord(*m_source, m_name, m_header);
    if (m_laszip.recordLength() != m_header.recordLength)
        throwInvalidLaz(m_name, "the LASzip items add up to " +
                                    std::to_string(m_laszip.recordLength()) +
                                    " bytes per point, but the header's point record length is " +
                                    std::to_string(m_header.recordLength));
    ChunkList list = locateChunks(*m_source, m_name, m_header, m_laszip);
    m_chunks = std::move(list.chunks);
    m_origin = list.origin;
}

std::string LazFile::chunkLabel(std::size_t index) const {
    return "chunk " + std::to_string(index + 1) + " of " + std::to_string(m_chunks.size());
}

void LazFile::readChunk(std::size_t index, std::vector<std::byte>& bytes) const {
    const LazChunk& chunk = m_chunks.at(index);
    bytes.resize(static_cast<std::size_t>(chunk.byteCount));
    m_source->read(chunk.offset, bytes);
}

void LazFile::readBytes(std::uint64_t offset, std::span<std::byte> out) const {
    if (offset > m_source->size() || out.size() > m_source->size() - offset)
        throw std::out_of_range("LazFile::readBytes: bytes " + std::to_string(offset) + " + " +
                                std::to_string(out.size()) + " outside the file of " +
                                std::to_string(m_source->size()));
    m_source->read(offset, out);
}

} // namespace terratin::io::laz

/// @file
/// LazFile: the LAS header, the VLRs and the LASzip record of a LAZ file (see laz_file.hpp),
/// read by the LAS header parser; every offset and length is checked against the file size
/// before anything is read at it.

#include "laz_file.hpp"

#include "chunk_table.hpp"
#include "laz_error.hpp"

#include <stdexcept>

namespace terratin::io::laz {

LazFile::LazFile(const detail::ByteSource& source, std::string name)
    : m_source(&source), m_name(std::move(name)) {}

LazFile LazFile::open(const std::string& path) {
    auto source = std::make_unique<detail::FileSource>(path, kLazStage);
    LazFile file(*source, path);
    file.m_ownSource = std::move(source);
    file.place(detail::parseHeader(*file.m_source, file.m_name));
    return file;
}

LazFile LazFile::fromMemory(std::span<const std::byte> bytes, std::string name) {
    auto source = std::make_unique<detail::MemorySource>(bytes);
    LazFile file(*source, std::move(name));
    file.m_ownSource = std::move(source);
    file.place(detail::parseHeader(*file.m_source, file.m_name));
    return file;
}

LazFile LazFile::fromParsedHeader(const detail::ByteSource& source, std::string name,
                                  const detail::ParsedHeader& parsed) {
    LazFile file(source, std::move(name));
    file.place(parsed);
    return file;
}

void LazFile::place(const detail::ParsedHeader& parsed) {
    m_header = parsed.header;
    if (!m_header.compressed || !parsed.laszipRecord)
        throwInvalidLaz(m_name, "no LASzip record (VLR 'laszip encoded' 22204) and no "
                                "compression mark in the point format: not a LAZ file");
    m_laszip = parseLaszipRecord(*parsed.laszipRecord, m_name);
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

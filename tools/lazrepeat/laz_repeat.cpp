/// @file
/// terratin-lazrepeat's work (see laz_repeat.hpp): the input placed by the project's LAZ
/// reader (LazFile), its parts read once, then each output written from them under a
/// temporary name and renamed into place at the end.
///
/// Layout of the repeated file: header and VLRs | chunk table pointer (i64) | the input's
/// chunks, copies times | chunk table (u32 version 0, u32 count, coded entries) | EVLRs.

#include "laz_repeat.hpp"

#include "atomic_output.hpp"
#include "buffered_file.hpp"
#include "chunk_decoder.hpp"
#include "chunk_table.hpp"
#include "laz_bytes.hpp"
#include "laz_encoder.hpp"
#include "laz_file.hpp"
#include "repeated_header.hpp"
#include "terratin/error.hpp"

#include <array>
#include <limits>
#include <span>
#include <string>
#include <system_error>
#include <vector>

namespace terratin::lazrepeat {

namespace {

namespace fs = std::filesystem;
using io::laz::LazFile;

constexpr std::uint64_t kPointerBytes = 8;
constexpr std::uint64_t kMaxTableValue = std::numeric_limits<std::uint32_t>::max();

/// What of the input the outputs are made of.
struct InputParts {
    /// The header and VLRs: the file's bytes before its point data.
    std::vector<std::byte> prefix;
    VlrPlace laszip;
    /// The chunks, back to back, as in the input.
    std::vector<std::byte> chunks;
    std::vector<io::laz::ChunkTableEntry> entries;
    TailRange tail;
    std::vector<std::byte> tailBytes;
};

/// Refuses a LAZ file whose chunks cannot simply be repeated `copies` times.
void checkRepeatable(const LazFile& file, std::uint32_t copies) {
    const io::laz::LaszipRecord& laszip = file.laszip();
    if (!laszip.chunked())
        throwInvalid(file.name(),
                     "compressor " + std::to_string(static_cast<int>(laszip.compressor)) +
                         (laszip.compressor == io::laz::Compressor::Pointwise
                              ? " (pointwise, unchunked)"
                              : " (none)") +
                         " stores the points as one stream, with no chunks to repeat; give a "
                         "chunked LAZ file (compressor 2 or 3, what laszip writes by default)");
    const std::vector<io::laz::LazChunk>& chunks = file.chunks();
    if (chunks.empty())
        throwInvalid(file.name(), "no points to repeat");
    if (chunks.size() > kMaxTableValue / copies)
        throwInvalid(file.name(), std::to_string(copies) + " copies of " +
                                      std::to_string(chunks.size()) +
                                      " chunks are more than a chunk table counts (2^32 - 1)");
    // The chunks are copied as one block: they must lie back to back after the pointer.
    std::uint64_t expected = file.header().pointDataOffset + kPointerBytes;
    for (std::size_t i = 0; i < chunks.size(); ++i) {
        if (chunks[i].offset != expected)
            throwInvalid(file.name(), file.chunkLabel(i) + " starts at byte " +
                                          std::to_string(chunks[i].offset) + ", not at byte " +
                                          std::to_string(expected) +
                                          " where the chunk before it ends");
        if (chunks[i].byteCount > kMaxTableValue || chunks[i].pointCount > kMaxTableValue)
            throwInvalid(file.name(), file.chunkLabel(i) + " is larger than a chunk table entry "
                                                           "holds (2^32 - 1 points or bytes)");
        expected += chunks[i].byteCount;
    }
}

InputParts readParts(const LazFile& file, std::uint32_t copies) {
    checkRepeatable(file, copies);
    InputParts parts;
    parts.prefix.resize(file.header().pointDataOffset);
    file.readBytes(0, parts.prefix);
    parts.laszip = findLaszipVlr(parts.prefix, file.header(), file.name());
    const io::laz::LazChunk& first = file.chunks().front();
    const io::laz::LazChunk& last = file.chunks().back();
    parts.chunks.resize(static_cast<std::size_t>(last.offset + last.byteCount - first.offset));
    file.readBytes(first.offset, parts.chunks);
    for (const io::laz::LazChunk& chunk : file.chunks())
        parts.entries.push_back({static_cast<std::uint32_t>(chunk.pointCount),
                                 static_cast<std::uint32_t>(chunk.byteCount)});
    parts.tail = locateTail(file, parts.prefix);
    parts.tailBytes.resize(static_cast<std::size_t>(parts.tail.end - parts.tail.start));
    file.readBytes(parts.tail.start, parts.tailBytes);
    return parts;
}

/// Every point of the input as LAS records, decoded chunk by chunk.
std::vector<std::byte> decodeRecordsOf(const LazFile& file) {
    io::laz::ChunkDecoder decoder(file.laszip(), file.name());
    const std::size_t length = file.header().recordLength;
    std::vector<std::byte> records(length * static_cast<std::size_t>(file.header().pointCount));
    std::vector<std::byte> bytes;
    for (std::size_t i = 0; i < file.chunks().size(); ++i) {
        const io::laz::LazChunk& chunk = file.chunks()[i];
        file.readChunk(i, bytes);
        const std::span<std::byte> out(records.data() + chunk.firstPoint * length,
                                       static_cast<std::size_t>(chunk.pointCount) * length);
        decoder.decode(bytes, chunk.pointCount, out, file.chunkLabel(i));
    }
    return records;
}

/// decodeRecordsOf, its errors saying that only the twin needs the decoding.
std::vector<std::byte> decodeRecords(const LazFile& file) {
    try {
        return decodeRecordsOf(file);
    } catch (const InvalidInputError& error) {
        // The repeated LAZ file needs no decoding: say that it can still be had.
        throw InvalidInputError(error.markedMessage() +
                                " (needed for the LAS twin only: without --las the LAZ "
                                "file is written from the chunks as they are)");
    }
}

/// `bytes` to `out`; nothing for none (BufferedFile would memcpy from a null pointer).
void put(io::detail::BufferedFile& out, std::span<const std::byte> bytes) {
    if (!bytes.empty())
        out.bytes(bytes.data(), bytes.size());
}

/// Writes the repeated LAZ file to `path` (named `display` in errors); returns its size.
std::uint64_t writeRepeatedLaz(const InputParts& parts, const LazFile& file, std::uint32_t copies,
                               const fs::path& path, const fs::path& display) {
    std::vector<std::byte> prefix = parts.prefix;
    scalePointCounts(prefix, file.header(), copies, file.name());
    markVariableChunks(prefix, parts.laszip);
    std::vector<io::laz::ChunkTableEntry> entries;
    entries.reserve(parts.entries.size() * copies);
    for (std::uint32_t copy = 0; copy < copies; ++copy)
        entries.insert(entries.end(), parts.entries.begin(), parts.entries.end());
    const std::vector<std::byte> table = encodeChunkTable(entries, true);
    const std::uint64_t tableStart =
        prefix.size() + kPointerBytes + std::uint64_t{copies} * parts.chunks.size();
    moveTailOffsets(prefix, file.header(), parts.tail, tableStart + table.size());
    std::array<std::byte, kPointerBytes> pointer{};
    io::laz::storeLe(pointer.data(), static_cast<std::int64_t>(tableStart));

    io::detail::BufferedFile out(kStage, path, display);
    put(out, prefix);
    put(out, pointer);
    for (std::uint32_t copy = 0; copy < copies; ++copy)
        put(out, parts.chunks);
    put(out, table);
    put(out, parts.tailBytes);
    out.close();
    return tableStart + table.size() + parts.tailBytes.size();
}

/// Writes the uncompressed twin of the repeated file; returns its size.
std::uint64_t writeLasTwin(const InputParts& parts, const LazFile& file,
                           const std::vector<std::byte>& records, std::uint32_t copies,
                           const fs::path& path, const fs::path& display) {
    std::vector<std::byte> scaled = parts.prefix;
    scalePointCounts(scaled, file.header(), copies, file.name());
    std::vector<std::byte> prefix = uncompressedPrefix(scaled, parts.laszip);
    const std::uint64_t pointsEnd = prefix.size() + std::uint64_t{copies} * records.size();
    moveTailOffsets(prefix, file.header(), parts.tail, pointsEnd);

    io::detail::BufferedFile out(kStage, path, display);
    put(out, prefix);
    for (std::uint32_t copy = 0; copy < copies; ++copy)
        put(out, records);
    put(out, parts.tailBytes);
    out.close();
    return pointsEnd + parts.tailBytes.size();
}

bool samePlace(const fs::path& a, const fs::path& b) {
    std::error_code error;
    if (fs::absolute(a, error).lexically_normal() == fs::absolute(b, error).lexically_normal())
        return true;
    return fs::exists(a, error) && fs::exists(b, error) && fs::equivalent(a, b, error);
}

void checkRequest(const RepeatRequest& request) {
    const std::string input = request.input.string();
    if (request.copies == 0)
        throwInvalid(input, "0 copies: give at least 1");
    if (samePlace(request.input, request.output))
        throwInvalid(input, "the output is the input itself");
    if (request.lasTwin && samePlace(request.input, *request.lasTwin))
        throwInvalid(input, "the LAS output is the input itself");
    if (request.lasTwin && samePlace(request.output, *request.lasTwin))
        throwInvalid(input, "the LAZ and the LAS output are the same file");
}

} // namespace

RepeatSummary repeatLaz(const RepeatRequest& request) {
    checkRequest(request);
    std::vector<fs::path> outputs{request.output};
    if (request.lasTwin)
        outputs.push_back(*request.lasTwin);
    io::detail::refuseExistingOutputs(kStage, outputs, request.overwrite);

    const LazFile file = LazFile::open(request.input.string());
    const InputParts parts = readParts(file, request.copies);
    // Decoded before anything is written: a point layout the decoder refuses costs no output.
    const std::vector<std::byte> records =
        request.lasTwin ? decodeRecords(file) : std::vector<std::byte>{};

    const io::detail::ExistingTarget existing = io::detail::existingTargetFor(request.overwrite);
    const io::detail::AtomicOutput lazOutput(kStage, request.output, existing);
    const fs::path lazTemporary = lazOutput.temporary(request.output.extension().string());
    RepeatSummary summary;
    summary.lazBytes = writeRepeatedLaz(parts, file, request.copies, lazTemporary, request.output);
    std::optional<io::detail::AtomicOutput> lasOutput;
    fs::path lasTemporary;
    if (request.lasTwin) {
        lasOutput.emplace(kStage, *request.lasTwin, existing);
        lasTemporary = lasOutput->temporary(request.lasTwin->extension().string());
        summary.lasBytes =
            writeLasTwin(parts, file, records, request.copies, lasTemporary, *request.lasTwin);
    }
    lazOutput.commit(lazTemporary, request.output);
    if (lasOutput)
        lasOutput->commit(lasTemporary, *request.lasTwin);

    summary.inputPoints = file.header().pointCount;
    summary.inputChunks = file.chunks().size();
    summary.points = summary.inputPoints * request.copies;
    summary.chunks = summary.inputChunks * request.copies;
    return summary;
}

} // namespace terratin::lazrepeat

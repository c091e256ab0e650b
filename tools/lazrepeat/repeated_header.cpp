/// @file
/// Patching the input's header and VLR bytes for the repeated file and its twin (see
/// repeated_header.hpp). The header parser (lib/src/io/las_header.cpp) has checked sizes and
/// offsets already; the checks here guard only what this file itself reads.

#include "repeated_header.hpp"

#include "laszip_vlr.hpp"
#include "laz_bytes.hpp"
#include "terratin/error.hpp"

#include <algorithm>
#include <array>
#include <limits>
#include <optional>

namespace terratin::lazrepeat {

namespace {

using io::laz::loadLe;
using io::laz::storeLe;

/// Fields of the public header block (LAS 1.4 R15, table 3).
constexpr std::size_t kGlobalEncodingAt = 6;
constexpr std::size_t kPointDataOffsetAt = 96;
constexpr std::size_t kVlrCountAt = 100;
constexpr std::size_t kPointFormatAt = 104;
constexpr std::size_t kLegacyPointCountAt = 107;
constexpr std::size_t kLegacyReturnCountsAt = 111;
constexpr std::size_t kLegacyReturnCounts = 5;
constexpr std::size_t kWaveformStartAt = 227; // 1.3 on
constexpr std::size_t kEvlrStartAt = 235;     // 1.4 on
constexpr std::size_t kPointCountAt = 247;    // 1.4 on
constexpr std::size_t kReturnCountsAt = 255;  // 1.4 on
constexpr std::size_t kReturnCounts = 15;
constexpr std::size_t kHeaderSize13 = 235;
constexpr std::size_t kHeaderSize14 = 375;
/// Global encoding bit 1: the waveform data packets are inside the file (LAS 1.3 on).
constexpr std::uint16_t kInternalWaveform = 1u << 1;
/// VLR and EVLR headers: reserved u16, user id [16], record id u16, length, description [32].
constexpr std::size_t kVlrHeaderSize = 54;
constexpr std::size_t kEvlrHeaderSize = 60;
constexpr std::size_t kUserIdAt = 2;
constexpr std::size_t kUserIdSize = 16;
constexpr std::size_t kRecordIdAt = 18;
constexpr std::size_t kLengthAt = 20;
/// The chunk size inside the LASzip VLR's payload (laszip_vlr.hpp).
constexpr std::size_t kChunkSizeInPayload = 12;
constexpr std::uint32_t kVariableChunkSize = 0xFFFFFFFFu;
/// Bits 7 (LASzip) and 6 (LASzip's LAS 1.4 formats) of the point format byte.
constexpr std::uint8_t kCompressionBits = 0xC0;

constexpr std::uint64_t kMaxLegacyCount = std::numeric_limits<std::uint32_t>::max();

std::string vlrUserId(std::span<const std::byte> vlr) {
    const auto* text = reinterpret_cast<const char*>(vlr.data() + kUserIdAt);
    return std::string(text, std::find(text, text + kUserIdSize, '\0'));
}

/// `count` x `copies`, or InvalidInputError saying what did not fit where.
std::uint64_t multiplied(std::uint64_t count, std::uint32_t copies, std::uint64_t limit,
                         const std::string& what, std::string_view fileName) {
    if (count != 0 && copies > limit / count)
        throwInvalid(fileName, std::to_string(copies) + " copies of " + std::to_string(count) +
                                   " make more " + what + " than the header can hold (" +
                                   std::to_string(limit) + "); use fewer copies");
    return count * copies;
}

/// The legacy 32-bit counts at bytes 107-130. `total` is the new point count; LAS 1.4 sets
/// them to 0 when it does not fit, earlier versions have no other count and refuse it.
void scaleLegacyCounts(std::span<std::byte> prefix, const io::LasHeader& header,
                       std::uint32_t copies, std::uint64_t total, std::string_view fileName) {
    const bool las14 = header.versionMinor >= 4;
    const bool inputKeptLegacy = loadLe<std::uint32_t>(prefix.data() + kLegacyPointCountAt) != 0;
    if (las14 && (!inputKeptLegacy || total > kMaxLegacyCount)) {
        std::fill_n(prefix.begin() + kLegacyPointCountAt, 4 + 4 * kLegacyReturnCounts,
                    std::byte{0});
        return;
    }
    const std::string version = "LAS 1." + std::to_string(header.versionMinor);
    storeLe(prefix.data() + kLegacyPointCountAt,
            static_cast<std::uint32_t>(
                multiplied(header.pointCount, copies, kMaxLegacyCount, "points", fileName)));
    for (std::size_t r = 0; r < kLegacyReturnCounts; ++r) {
        std::byte* at = prefix.data() + kLegacyReturnCountsAt + 4 * r;
        const std::uint64_t count =
            multiplied(loadLe<std::uint32_t>(at), copies, kMaxLegacyCount,
                       version + " return " + std::to_string(r + 1) + " counts", fileName);
        storeLe(at, static_cast<std::uint32_t>(count));
    }
}

/// The end of `count` (E)VLRs from `start`, each with its 60-byte header, within `fileSize`.
std::uint64_t evlrsEnd(const io::laz::LazFile& file, std::uint64_t start, std::uint32_t count) {
    std::uint64_t at = start;
    for (std::uint32_t i = 0; i < count; ++i) {
        if (at > file.fileSize() || kEvlrHeaderSize > file.fileSize() - at)
            throwInvalid(file.name(), "extended variable length record " + std::to_string(i + 1) +
                                          " of " + std::to_string(count) +
                                          " runs past the end of the file");
        std::array<std::byte, kEvlrHeaderSize> evlr{};
        file.readBytes(at, evlr);
        const auto length = loadLe<std::uint64_t>(evlr.data() + kLengthAt);
        if (length > file.fileSize() - at - kEvlrHeaderSize)
            throwInvalid(file.name(), "extended variable length record " + std::to_string(i + 1) +
                                          " of " + std::to_string(count) +
                                          " runs past the end of the file");
        at += kEvlrHeaderSize + length;
    }
    return at;
}

} // namespace

void throwInvalid(std::string_view fileName, const std::string& what) {
    throw InvalidInputError(std::string(kStage) + ": '" + std::string(fileName) + "': " + what);
}

VlrPlace findLaszipVlr(std::span<const std::byte> prefix, const io::LasHeader& header,
                       std::string_view fileName) {
    std::size_t at = header.headerSize;
    std::optional<VlrPlace> laszip;
    for (std::uint32_t i = 0; i < header.vlrCount; ++i) {
        if (at + kVlrHeaderSize > prefix.size())
            throwInvalid(fileName, "VLR " + std::to_string(i + 1) + " runs into the point data");
        const std::span<const std::byte> vlr = prefix.subspan(at, kVlrHeaderSize);
        const std::size_t size = kVlrHeaderSize + loadLe<std::uint16_t>(vlr.data() + kLengthAt);
        const std::string userId = vlrUserId(vlr);
        const auto recordId = loadLe<std::uint16_t>(vlr.data() + kRecordIdAt);
        if (userId == "copc" && recordId == 1)
            throwInvalid(fileName, "a COPC file: its hierarchy addresses the input's own chunks, "
                                   "so repeating them would not make a valid COPC file; give "
                                   "a plain LAZ file");
        if (userId == io::laz::kLaszipUserId && recordId == io::laz::kLaszipRecordId)
            laszip = VlrPlace{at, size};
        at += size;
    }
    if (!laszip || laszip->offset + laszip->size > prefix.size() ||
        laszip->size < kVlrHeaderSize + kChunkSizeInPayload + 4)
        throwInvalid(fileName, "no LASzip VLR among the VLRs before the point data");
    return *laszip;
}

void scalePointCounts(std::span<std::byte> prefix, const io::LasHeader& header,
                      std::uint32_t copies, std::string_view fileName) {
    const std::uint64_t limit =
        header.versionMinor >= 4 ? std::numeric_limits<std::uint64_t>::max() : kMaxLegacyCount;
    const std::string version = "LAS 1." + std::to_string(header.versionMinor);
    const std::uint64_t total = multiplied(header.pointCount, copies, limit,
                                           "points than " + version + " allows", fileName);
    scaleLegacyCounts(prefix, header, copies, total, fileName);
    if (header.versionMinor < 4 || prefix.size() < kHeaderSize14)
        return;
    storeLe(prefix.data() + kPointCountAt, total);
    for (std::size_t r = 0; r < kReturnCounts; ++r) {
        std::byte* at = prefix.data() + kReturnCountsAt + 8 * r;
        storeLe(at, multiplied(loadLe<std::uint64_t>(at), copies, limit,
                               "return " + std::to_string(r + 1) + " counts", fileName));
    }
}

TailRange locateTail(const io::laz::LazFile& file, std::span<const std::byte> prefix) {
    const io::LasHeader& header = file.header();
    std::uint64_t start = 0;
    std::uint32_t count = 0;
    if (header.versionMinor >= 4 && header.evlrCount > 0) {
        start = header.evlrStart;
        count = header.evlrCount;
    } else if (header.versionMinor >= 3 && prefix.size() >= kHeaderSize13 &&
               (loadLe<std::uint16_t>(prefix.data() + kGlobalEncodingAt) & kInternalWaveform) &&
               loadLe<std::uint64_t>(prefix.data() + kWaveformStartAt) != 0) {
        // LAS 1.3 keeps its waveform data in one EVLR, which only this offset finds.
        start = loadLe<std::uint64_t>(prefix.data() + kWaveformStartAt);
        count = 1;
    } else {
        return {};
    }
    const io::laz::LazChunk& last = file.chunks().back();
    if (start < last.offset + last.byteCount)
        throwInvalid(file.name(), "the extended variable length records start at byte " +
                                      std::to_string(start) +
                                      ", among the chunks; only records after the chunk table "
                                      "can be carried over");
    return {start, evlrsEnd(file, start, count)};
}

void moveTailOffsets(std::span<std::byte> prefix, const io::LasHeader& header,
                     const TailRange& tail, std::uint64_t newStart) {
    if (tail.empty())
        return;
    const auto moved = [&](std::size_t fieldAt) {
        const auto offset = loadLe<std::uint64_t>(prefix.data() + fieldAt);
        if (offset >= tail.start && offset < tail.end)
            storeLe(prefix.data() + fieldAt, offset - tail.start + newStart);
    };
    if (header.versionMinor >= 3 && prefix.size() >= kHeaderSize13)
        moved(kWaveformStartAt);
    if (header.versionMinor >= 4 && prefix.size() >= kHeaderSize14)
        moved(kEvlrStartAt);
}

void markVariableChunks(std::span<std::byte> prefix, const VlrPlace& laszip) {
    storeLe(prefix.data() + laszip.offset + kVlrHeaderSize + kChunkSizeInPayload,
            kVariableChunkSize);
}

std::vector<std::byte> uncompressedPrefix(std::span<const std::byte> prefix,
                                          const VlrPlace& laszip) {
    std::vector<std::byte> bytes(prefix.begin(), prefix.begin() + laszip.offset);
    bytes.insert(bytes.end(), prefix.begin() + laszip.offset + laszip.size, prefix.end());
    const auto pointFormat = loadLe<std::uint8_t>(bytes.data() + kPointFormatAt);
    storeLe(bytes.data() + kPointFormatAt,
            static_cast<std::uint8_t>(pointFormat & ~kCompressionBits));
    storeLe(bytes.data() + kVlrCountAt, loadLe<std::uint32_t>(bytes.data() + kVlrCountAt) - 1);
    storeLe(bytes.data() + kPointDataOffsetAt, static_cast<std::uint32_t>(bytes.size()));
    return bytes;
}

} // namespace terratin::lazrepeat

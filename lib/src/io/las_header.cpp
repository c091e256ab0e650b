#include "las_header.hpp"

#include "terratin/error.hpp"

#include <array>
#include <cerrno>
#include <cmath>

namespace terratin::io::detail {

namespace {

constexpr std::string_view kStage = kLasStage;

/// Bytes of the public header block by minor version (LAS 1.4 R15 table 3 and its ancestors).
constexpr std::uint16_t kHeaderSize12 = 227;
constexpr std::uint16_t kHeaderSize13 = 235;
constexpr std::uint16_t kHeaderSize14 = 375;
/// VLR and EVLR headers (2.5, 2.8).
constexpr std::uint64_t kVlrHeaderSize = 54;
constexpr std::uint64_t kEvlrHeaderSize = 60;
/// Minimum record length of point formats 0..10 (2.6, tables 7-17).
constexpr std::array<std::uint16_t, 11> kMinRecordLength{20, 28, 26, 34, 57, 63,
                                                         30, 36, 38, 59, 67};
[[noreturn]] void invalid(const std::string& name, const std::string& what) {
    throw InvalidInputError(std::string(kStage) + ": '" + name + "': " + what);
}

/// The slot of `parsed` for the record (`userId`, `recordId`), or null for one not kept.
std::optional<std::vector<std::byte>>* recordSlot(const std::string& userId, std::uint16_t recordId,
                                                  ParsedHeader& parsed) {
    if (userId == "laszip encoded")
        return recordId == 22204 ? &parsed.laszipRecord : nullptr;
    if (userId != "LASF_Projection")
        return nullptr;
    CrsRecords& records = parsed.crs;
    switch (recordId) {
    case 34735:
        return &records.geoKeys;
    case 34736:
        return &records.geoDoubles;
    case 34737:
        return &records.geoAscii;
    case 2112:
        return &records.wkt;
    default:
        return nullptr;
    }
}

void collectRecord(const ByteSource& source, const std::string& userId, std::uint16_t recordId,
                   std::uint64_t dataOffset, std::uint64_t length, ParsedHeader& parsed) {
    std::optional<std::vector<std::byte>>* const slot = recordSlot(userId, recordId, parsed);
    if (slot == nullptr)
        return;
    // CRS and LASzip records are small; an EVLR may claim a 64-bit length, bounded by the
    // file size already, but none needs more than a few MiB.
    constexpr std::uint64_t kMaxKeptRecord = std::uint64_t{16} << 20;
    if (length > kMaxKeptRecord)
        return;
    std::vector<std::byte> bytes(static_cast<std::size_t>(length));
    source.read(dataOffset, bytes);
    *slot = std::move(bytes);
}

/// Refuses what is no LAS file before anything else is read: the signature, then a file too
/// short for a header.
void checkSignature(const ByteSource& source, const std::string& name) {
    const std::uint64_t fileSize = source.size();
    if (fileSize < 4)
        invalid(name, "not a LAS file (" + std::to_string(fileSize) + " bytes, no LASF signature)");
    std::array<std::byte, 4> signature{};
    source.read(0, signature);
    if (std::memcmp(signature.data(), "LASF", 4) != 0)
        invalid(name, "not a LAS file (no LASF signature)");
    if (fileSize < kHeaderSize12)
        invalid(name, "truncated: " + std::to_string(fileSize) +
                          " bytes, shorter than a LAS header (227 bytes)");
}

/// The fields of the LAS 1.0-1.2 header (its first 227 bytes, `bytes`), the version and the
/// point format checked; pointCount is the legacy count.
LasHeader decodeHeader(std::span<const std::byte> bytes, const std::string& name) {
    LasHeader h;
    h.versionMajor = static_cast<int>(field<std::uint8_t>(bytes, 24));
    h.versionMinor = static_cast<int>(field<std::uint8_t>(bytes, 25));
    if (h.versionMajor != 1 || h.versionMinor > 4)
        invalid(name, "LAS version " + std::to_string(h.versionMajor) + "." +
                          std::to_string(h.versionMinor) + " is not supported (1.0 to 1.4 are)");
    h.globalEncoding = field<std::uint16_t>(bytes, 6);
    h.headerSize = field<std::uint16_t>(bytes, 94);
    h.pointDataOffset = field<std::uint32_t>(bytes, 96);
    h.vlrCount = field<std::uint32_t>(bytes, 100);
    // LASzip marks compressed files by setting bit 7 of the point format, and bit 6 as well
    // for the LAS 1.4 formats; what is left is a format of 0..10. Any other byte (99 = bit 6
    // and 35, say) is an unsupported format.
    const unsigned formatByte = field<std::uint8_t>(bytes, 104);
    h.compressed = (formatByte & 0x80u) != 0 && (formatByte & 0x3Fu) <= 10;
    h.pointFormat = static_cast<int>(h.compressed ? formatByte & 0x3Fu : formatByte);
    h.recordLength = field<std::uint16_t>(bytes, 105);
    h.pointCount = field<std::uint32_t>(bytes, 107);
    for (std::size_t axis = 0; axis < 3; ++axis) {
        h.scale[axis] = field<double>(bytes, 131 + 8 * axis);
        h.offset[axis] = field<double>(bytes, 155 + 8 * axis);
        // Header order: max x, min x, max y, min y, max z, min z.
        h.bounds[axis + 3] = field<double>(bytes, 179 + 16 * axis);
        h.bounds[axis] = field<double>(bytes, 187 + 16 * axis);
    }
    if (h.pointFormat > 10)
        invalid(name, "point data record format " + std::to_string(h.pointFormat) +
                          " is not supported (0 to 10 are)");
    return h;
}

/// The header's size against its version's and the file's.
void checkHeaderSize(const LasHeader& h, std::uint64_t fileSize, const std::string& name) {
    const std::uint16_t minHeader = h.versionMinor >= 4   ? kHeaderSize14
                                    : h.versionMinor == 3 ? kHeaderSize13
                                                          : kHeaderSize12;
    if (h.headerSize < minHeader)
        invalid(name, "header size " + std::to_string(h.headerSize) + " is below the " +
                          std::to_string(minHeader) + " bytes of a LAS 1." +
                          std::to_string(h.versionMinor) + " header");
    if (h.headerSize > fileSize)
        invalid(name, "truncated: the header declares " + std::to_string(h.headerSize) +
                          " bytes but the file has " + std::to_string(fileSize));
}

/// Where the EVLRs of LAS 1.4 are.
struct EvlrPlace {
    std::uint64_t start = 0;
    std::uint32_t count = 0;
};

/// LAS 1.4's fields after byte 227 (of `bytes`, the whole 375-byte header): the EVLRs' place,
/// and the 64-bit point count, which replaces the legacy one in `h` when set.
EvlrPlace decodeLas14Fields(std::span<const std::byte> bytes, LasHeader& h,
                            const std::string& name) {
    const EvlrPlace evlrs{field<std::uint64_t>(bytes, 235), field<std::uint32_t>(bytes, 243)};
    const std::uint64_t legacyCount = h.pointCount;
    const auto extendedCount = field<std::uint64_t>(bytes, 247);
    if (extendedCount != 0 && legacyCount != 0 && extendedCount != legacyCount)
        invalid(name, "the header's point counts disagree (legacy " + std::to_string(legacyCount) +
                          ", 64-bit " + std::to_string(extendedCount) + ")");
    if (extendedCount != 0)
        h.pointCount = extendedCount;
    return evlrs;
}

/// The scale, the record length and where the points lie, against the file; returns the end
/// of the point records (of LAZ: their start, the chunk table alone knowing their end).
std::uint64_t checkPointLayout(const LasHeader& h, std::uint64_t fileSize,
                               const std::string& name) {
    for (std::size_t axis = 0; axis < 3; ++axis) {
        if (!std::isfinite(h.scale[axis]) || h.scale[axis] == 0.0 || !std::isfinite(h.offset[axis]))
            invalid(name, std::string("the ") + "xyz"[axis] +
                              " scale factor or offset is zero or "
                              "not finite");
    }
    if (h.recordLength < kMinRecordLength[static_cast<std::size_t>(h.pointFormat)])
        invalid(name,
                "point record length " + std::to_string(h.recordLength) + " is below the " +
                    std::to_string(kMinRecordLength[static_cast<std::size_t>(h.pointFormat)]) +
                    " bytes of point format " + std::to_string(h.pointFormat));
    if (h.pointDataOffset < h.headerSize)
        invalid(name, "the point data offset " + std::to_string(h.pointDataOffset) +
                          " lies inside the " + std::to_string(h.headerSize) + "-byte header");
    if (h.pointDataOffset > fileSize)
        invalid(name, "truncated: the point data should start at byte " +
                          std::to_string(h.pointDataOffset) + " but the file has " +
                          std::to_string(fileSize) + " bytes");
    if (h.compressed)
        return h.pointDataOffset;
    const std::uint64_t available = fileSize - h.pointDataOffset;
    if (h.pointCount > available / h.recordLength)
        invalid(name, "truncated or lying header: it declares " + std::to_string(h.pointCount) +
                          " point records of " + std::to_string(h.recordLength) +
                          " bytes from byte " + std::to_string(h.pointDataOffset) +
                          ", but the file has room for " +
                          std::to_string(available / h.recordLength));
    return h.pointDataOffset + h.pointCount * h.recordLength;
}

/// The VLRs, between the header and the point data, each within that space.
void walkVlrs(const ByteSource& source, const LasHeader& h, const std::string& name,
              ParsedHeader& parsed) {
    const auto runsIntoPoints = [&](std::uint32_t i) {
        invalid(name, "variable length record " + std::to_string(i + 1) + " of " +
                          std::to_string(h.vlrCount) + " runs into the point data");
    };
    std::uint64_t pos = h.headerSize;
    for (std::uint32_t i = 0; i < h.vlrCount; ++i) {
        if (pos + kVlrHeaderSize > h.pointDataOffset)
            runsIntoPoints(i);
        std::array<std::byte, kVlrHeaderSize> vlr{};
        source.read(pos, vlr);
        const std::string userId = trimmedText(std::span<const std::byte>(vlr).subspan(2, 16));
        const auto recordId = field<std::uint16_t>(vlr, 18);
        const std::uint64_t length = field<std::uint16_t>(vlr, 20);
        if (pos + kVlrHeaderSize + length > h.pointDataOffset)
            runsIntoPoints(i);
        collectRecord(source, userId, recordId, pos + kVlrHeaderSize, length, parsed);
        pos += kVlrHeaderSize + length;
    }
}

/// The EVLRs (1.4), after the point data (which ends at `pointsEnd`), each within the file.
void walkEvlrs(const ByteSource& source, const EvlrPlace& evlrs, std::uint64_t pointsEnd,
               const std::string& name, ParsedHeader& parsed) {
    if (evlrs.count == 0)
        return;
    const std::uint64_t fileSize = source.size();
    if (evlrs.start < pointsEnd || evlrs.start > fileSize)
        invalid(name, "the extended variable length records start at byte " +
                          std::to_string(evlrs.start) + ", outside the bytes after the points");
    const auto runsPastTheEnd = [&](std::uint32_t i) {
        invalid(name, "truncated: extended variable length record " + std::to_string(i + 1) +
                          " of " + std::to_string(evlrs.count) + " runs past the end of the file");
    };
    std::uint64_t pos = evlrs.start;
    for (std::uint32_t i = 0; i < evlrs.count; ++i) {
        if (kEvlrHeaderSize > fileSize - pos)
            runsPastTheEnd(i);
        std::array<std::byte, kEvlrHeaderSize> evlr{};
        source.read(pos, evlr);
        const std::string userId = trimmedText(std::span<const std::byte>(evlr).subspan(2, 16));
        const auto recordId = field<std::uint16_t>(evlr, 18);
        const auto length = field<std::uint64_t>(evlr, 20);
        if (length > fileSize - pos - kEvlrHeaderSize)
            runsPastTheEnd(i);
        collectRecord(source, userId, recordId, pos + kEvlrHeaderSize, length, parsed);
        pos += kEvlrHeaderSize + length;
    }
}

} // namespace

ParsedHeader parseHeader(const ByteSource& source, const std::string& name) {
    checkSignature(source, name);
    const std::uint64_t fileSize = source.size();
    std::array<std::byte, kHeaderSize14> raw{};
    source.read(0, std::span(raw).first(kHeaderSize12));
    const std::span<const std::byte> bytes(raw);

    ParsedHeader parsed;
    LasHeader& h = parsed.header;
    h = decodeHeader(bytes, name);
    checkHeaderSize(h, fileSize, name);
    EvlrPlace evlrs;
    if (h.versionMinor >= 4) {
        source.read(kHeaderSize12,
                    std::span(raw).subspan(kHeaderSize12, kHeaderSize14 - kHeaderSize12));
        evlrs = decodeLas14Fields(bytes, h, name);
        h.evlrStart = evlrs.start;
        h.evlrCount = evlrs.count;
    }
    parsed.pointsEnd = checkPointLayout(h, fileSize, name);
    walkVlrs(source, h, name, parsed);
    walkEvlrs(source, evlrs, parsed.pointsEnd, name, parsed);
    // A LASzip record in a file whose format byte says uncompressed is a stale one (a tool
    // that decompressed the points kept it): the record sizes were checked as LAS above.
    if (h.compressed && !parsed.laszipRecord)
        invalid(name, "the point format is marked LASzip-compressed (LAZ), but there is no "
                      "LASzip record (VLR 'laszip encoded' 22204)");
    return parsed;
}

std::string trimmedText(std::span<const std::byte> bytes) {
    std::string text(reinterpret_cast<const char*>(bytes.data()), bytes.size());
    const std::size_t end = text.find('\0');
    if (end != std::string::npos)
        text.resize(end);
    return text;
}

} // namespace terratin::io::detail

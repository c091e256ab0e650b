#pragma once
/// @file
/// The `laszip encoded` variable length record (user id "laszip encoded", record id 22204):
/// how the point records of a LAZ file were compressed. Layout, all little-endian:
///
///   u16 compressor  0 none, 1 pointwise, 2 pointwise chunked, 3 layered chunked (LAS 1.4)
///   u16 coder       0 arithmetic, the only one defined
///   u8 version major, u8 version minor, u16 version revision   (of the writing LASzip)
///   u32 options     (reserved)
///   u32 chunk size  points per chunk; 0xFFFFFFFF (and 0): variable, listed in the chunk table
///   i64 number of special EVLRs, i64 offset of special EVLRs   (-1: none)
///   u16 item count, then per item: u16 type, u16 size, u16 version
///
/// The items, in order, make up one point record: their sizes add up to the record length.

#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace terratin::io::laz {

inline constexpr std::string_view kLaszipUserId = "laszip encoded";
inline constexpr std::uint16_t kLaszipRecordId = 22204;

enum class Compressor : std::uint16_t {
    None = 0,
    Pointwise = 1,
    PointwiseChunked = 2,
    LayeredChunked = 3,
};

/// The item types of the format; 1-5 (SHORT .. DOUBLE) are defined but never written.
enum class ItemType : std::uint16_t {
    Byte = 0, ///< extra bytes after a LAS 1.0-1.3 point
    Short = 1,
    Int = 2,
    Long = 3,
    Float = 4,
    Double = 5,
    Point10 = 6,      ///< the 20 bytes common to point formats 0-5
    GpsTime11 = 7,    ///< the 8-byte GPS time of formats 1, 3, 4, 5
    Rgb12 = 8,        ///< the 6-byte colour of formats 2, 3, 5
    WavePacket13 = 9, ///< the 29-byte wave packet of formats 4, 5
    Point14 = 10,     ///< the 30 bytes common to point formats 6-10
    Rgb14 = 11,
    RgbNir14 = 12,
    WavePacket14 = 13,
    Byte14 = 14, ///< extra bytes after a LAS 1.4 point (layered)
};

struct Item {
    ItemType type = ItemType::Byte;
    std::uint16_t size = 0;
    std::uint16_t version = 0;
};

/// "POINT10", "GPSTIME11", ... as LASzip names them; "type N" for an unknown type.
[[nodiscard]] std::string itemName(std::uint16_t type);

struct LaszipRecord {
    Compressor compressor = Compressor::None;
    std::uint16_t coder = 0;
    std::uint8_t versionMajor = 0;
    std::uint8_t versionMinor = 0;
    std::uint16_t versionRevision = 0;
    std::uint32_t options = 0;
    std::uint32_t chunkSize = 0;
    std::int64_t specialEvlrCount = -1;
    std::int64_t specialEvlrOffset = -1;
    std::vector<Item> items;

    /// Whether the chunk table lists each chunk's point count. LASzip reads a chunk size of 0
    /// like 0xFFFFFFFF: no fixed size (seen in COPC files).
    [[nodiscard]] bool variableChunks() const { return chunkSize == 0 || chunkSize == 0xFFFFFFFFu; }
    [[nodiscard]] bool chunked() const {
        return compressor == Compressor::PointwiseChunked ||
               compressor == Compressor::LayeredChunked;
    }
    /// The sum of the item sizes: the point record length.
    [[nodiscard]] std::uint32_t recordLength() const;
};

/// Parses and checks the payload of the LASzip VLR of the file `fileName` (named in errors):
/// the compressor (0-3), the coder (0), every item's type, size and version (those LASzip
/// defines), the payload length (34 + 6 x items). Throws InvalidInputError, one line naming
/// the file and what is wrong, e.g. "coder 15 is not the arithmetic coder (0), the only one
/// LASzip defines".
[[nodiscard]] LaszipRecord parseLaszipRecord(std::span<const std::byte> payload,
                                             std::string_view fileName);

} // namespace terratin::io::laz

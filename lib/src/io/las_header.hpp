#pragma once
/// @file
/// The LAS header and its variable length records, read from a ByteSource and checked against
/// its size before anything is read at an offset it declares (LAS 1.4 R15, 2.4-2.8): the
/// public header block is read at fixed byte offsets; 1.0-1.2 stop at byte 227, 1.3 adds the
/// waveform offset (to 235), 1.4 the EVLR start and count and the 64-bit point counts (to
/// 375). A LAZ file (LASzip's compression bit in the point format byte) is recognised here:
/// its header is the same, its points are the LAZ reader's (lib/src/io/laz).

#include "byte_source.hpp"
#include "terratin/io/las_reader.hpp"

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace terratin::io::detail {

inline constexpr std::string_view kLasStage = "LasReader";

/// A little-endian field at `pos` of `bytes`; memcpy keeps it free of alignment and aliasing
/// problems. Precondition: pos + sizeof(T) <= bytes.size().
template <typename T> T field(std::span<const std::byte> bytes, std::size_t pos) {
    T value;
    std::memcpy(&value, bytes.data() + pos, sizeof(T));
    return value;
}

/// `bytes` as text, up to the first NUL.
std::string trimmedText(std::span<const std::byte> bytes);

/// The CRS records found among the (E)VLRs.
struct CrsRecords {
    std::optional<std::vector<std::byte>> geoKeys;    // 34735
    std::optional<std::vector<std::byte>> geoDoubles; // 34736
    std::optional<std::vector<std::byte>> geoAscii;   // 34737
    std::optional<std::vector<std::byte>> wkt;        // 2112
};

/// The header as read and checked, the CRS records of its (E)VLRs, the payload of the LASzip
/// VLR (user "laszip encoded", record 22204) of a LAZ file, and the end of the point records
/// (for LAZ: of the header and VLRs, since only the chunk table knows where its points end).
struct ParsedHeader {
    LasHeader header;
    CrsRecords crs;
    std::optional<std::vector<std::byte>> laszipRecord;
    std::uint64_t pointsEnd = 0;
};

/// The header of `source`, checked against its size, and the CRS records of its (E)VLRs;
/// InvalidInputError naming `name` for what is no LAS or LAZ file or disagrees with the
/// file's size (for LAZ the compressed records are checked by the LAZ reader); IoError when
/// reading fails.
ParsedHeader parseHeader(const ByteSource& source, const std::string& name);

} // namespace terratin::io::detail

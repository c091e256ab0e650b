#pragma once
/// @file
/// LasReader: ASPRS LAS 1.0-1.4 point clouds (uncompressed, point data record formats 0-10) to
/// points, with class and return filters. An own little-endian binary parser: every header
/// field is checked against the size of the file before it is used, so a truncated or lying
/// file is an InvalidInputError, never an out-of-bounds read.
///
/// Reference: ASPRS, "LAS Specification 1.4 - R15" (2019), sections 2.4 (header), 2.5 (VLRs),
/// 2.6 (point data records), 2.8 (EVLRs); earlier versions are prefixes of the 1.4 header.

#include "terratin/io/point_source.hpp"
#include "terratin/progress.hpp"

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace terratin::io {

/// Which returns of a multi-return pulse to keep.
enum class LasReturns {
    All,   ///< every return
    First, ///< return number 1 (a return number of 0, invalid but seen, counts as first)
    Last,  ///< return number == number of returns (or greater, which is invalid but seen)
};

/// What to keep of a LAS file.
struct LasReadOptions {
    /// Classification codes to keep (ASPRS: 2 = ground); empty keeps every class.
    std::vector<int> classes;
    LasReturns returns = LasReturns::All;
    /// Threads decoding a LAZ file's chunks (0: every hardware thread); the points come in
    /// file order whatever the number.
    unsigned threads = 0;
};

/// The public header block, as far as the reader uses it, after validation.
struct LasHeader {
    int versionMajor = 1;
    int versionMinor = 0;
    std::uint16_t headerSize = 0;
    std::uint32_t pointDataOffset = 0;
    std::uint32_t vlrCount = 0;
    /// Point data record format, 0-10 (without LASzip's compression bits).
    int pointFormat = 0;
    /// LAZ: the point records are LASzip-compressed (bit 7 of the header's format byte).
    bool compressed = false;
    std::uint16_t recordLength = 0;
    /// The number of point records: the 64-bit count of LAS 1.4 when set, else the legacy one.
    std::uint64_t pointCount = 0;
    std::array<double, 3> scale{1.0, 1.0, 1.0};
    std::array<double, 3> offset{0.0, 0.0, 0.0};
    /// Bounds from the header (min x, min y, min z, max x, max y, max z), in CRS units.
    std::array<double, 6> bounds{};
    std::uint16_t globalEncoding = 0;
    /// LAS 1.4: where the extended VLRs start and how many there are; 0 and 0 otherwise.
    std::uint64_t evlrStart = 0;
    std::uint32_t evlrCount = 0;
};

/// Reads the LAS file at `path`: points x = X * scale + offset (same for y, z), in file order,
/// keeping those that pass `options` (withheld points are always dropped: the specification
/// calls them deleted). The CRS comes from the WKT (E)VLR when the header's WKT bit is set,
/// else from the GeoTIFF key VLRs (interpreted by GDAL's own GeoTIFF reader), else from a WKT
/// VLR written without the bit; empty when there is none.
/// Reads the point records through a bounded buffer (about 4 MiB).
/// `progress` is called after each buffer with the fraction of records read.
/// Throws IoError when the file cannot be opened or read; InvalidInputError for a file that
/// is not LAS, is LAZ ("LAZ is compressed; not supported"), has an unsupported version or
/// point format, or whose header, VLRs or point count disagree with its size; CrsError for
/// GeoTIFF keys or WKT that GDAL cannot interpret; Cancelled when `progress` returns false.
/// Complexity: O(records) time; 24 bytes per kept point.
PointCloud readLasPoints(const std::string& path, const LasReadOptions& options = {},
                         const ProgressCallback& progress = {});

/// The same, from a LAS file held in memory; `name` appears in messages and in
/// PointCloud::path. Used by the fuzzer and by tests.
PointCloud readLasPointsFromMemory(std::span<const std::byte> data, const std::string& name,
                                   const LasReadOptions& options = {},
                                   const ProgressCallback& progress = {});

/// The validated header of the LAS file at `path` (no point is read).
LasHeader readLasHeader(const std::string& path);

} // namespace terratin::io

#pragma once
// LAS files written by the tests: known points in any version 1.0-1.4 and point format 0-10,
// with optional (E)VLRs, so that the reader is checked against values fixed here, independently
// of any LAS library.

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace terratin::test {

/// One point record as stored (integers before scale and offset).
struct LasTestPoint {
    std::int32_t x = 0;
    std::int32_t y = 0;
    std::int32_t z = 0;
    std::uint8_t returnNumber = 1;
    std::uint8_t returnCount = 1;
    std::uint8_t classification = 1;
    bool withheld = false;
};

/// A variable length record (or an extended one, in LasTestFile::evlrs).
struct LasTestRecord {
    std::string userId;
    std::uint16_t recordId = 0;
    std::vector<std::byte> data;
};

/// A LAS file to write.
struct LasTestFile {
    int versionMinor = 2;
    int pointFormat = 1;
    /// Bytes added to each record beyond the format's minimum (extra bytes).
    int extraRecordBytes = 0;
    std::array<double, 3> scale{0.01, 0.01, 0.01};
    std::array<double, 3> offset{0.0, 0.0, 0.0};
    bool wktBit = false;
    std::vector<LasTestPoint> points;
    std::vector<LasTestRecord> vlrs;
    std::vector<LasTestRecord> evlrs;

    /// The file's bytes: header (227 / 235 / 375 bytes by version), VLRs, points, EVLRs; both
    /// point counts set for 1.4.
    [[nodiscard]] std::vector<std::byte> bytes() const;
};

/// The minimum record length of point format 0..10.
std::uint16_t lasMinimumRecordLength(int pointFormat);

/// LASF_Projection record 34735 holding a GeoKeyDirectory with ProjectedCSTypeGeoKey = `epsg`
/// (GTModelTypeGeoKey projected, GTRasterTypeGeoKey PixelIsArea).
LasTestRecord geoKeysForProjectedEpsg(std::uint16_t epsg);

/// LASF_Projection record 2112 holding `wkt` NUL-terminated.
LasTestRecord wktRecord(const std::string& wkt);

/// A little-endian value written into `bytes` at `pos` (for corrupting headers).
template <typename T> void poke(std::vector<std::byte>& bytes, std::size_t pos, T value);

} // namespace terratin::test

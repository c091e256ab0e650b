// Tests of LasReader: LAS files written here with known points (every version and point
// format), truncated and lying headers, and the real LAS files of TERRATIN_SHARED_DEMS checked
// against their own headers and known class counts.

#include "las_test_file.hpp"
#include "terratin/crs/reprojection.hpp"
#include "terratin/error.hpp"
#include "terratin/io/las_reader.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

namespace terratin::io {
namespace {

namespace fs = std::filesystem;
using test::LasTestFile;
using test::LasTestPoint;
using test::poke;

fs::path sharedFile(const std::string& name) {
    return fs::path(TERRATIN_SHARED_DEMS) / name;
}

/// A scratch file removed at the end of the test.
class ScratchFile {
public:
    explicit ScratchFile(const std::string& name)
        : m_path(fs::temp_directory_path() /
                 ("terratin_las_" +
                  std::to_string(::testing::UnitTest::GetInstance()->random_seed()) + "_" +
                  ::testing::UnitTest::GetInstance()->current_test_info()->name() + "_" + name)) {}
    ~ScratchFile() {
        std::error_code ignored;
        fs::remove(m_path, ignored);
    }
    ScratchFile(const ScratchFile&) = delete;
    ScratchFile& operator=(const ScratchFile&) = delete;
    void write(const std::vector<std::byte>& bytes) const {
        std::ofstream out(m_path, std::ios::binary);
        out.write(reinterpret_cast<const char*>(bytes.data()),
                  static_cast<std::streamsize>(bytes.size()));
    }
    [[nodiscard]] std::string path() const { return m_path.string(); }

private:
    fs::path m_path;
};

/// Five points covering the classification and return cases.
std::vector<LasTestPoint> samplePoints() {
    return {
        {100, 200, 300, 1, 1, 2, false},         // single return, ground
        {-100, 5, 7, 1, 3, 1, false},            // first of three, unclassified
        {7, 8, 9, 2, 3, 5, false},               // middle, high vegetation
        {1000000, -2000000, 12, 3, 3, 2, false}, // last of three, ground
        {1, 1, 1, 1, 1, 2, true},                // withheld ground: always dropped
    };
}

PointCloud readBytes(const std::vector<std::byte>& bytes, const LasReadOptions& options = {}) {
    return readLasPointsFromMemory(bytes, "test.las", options);
}

TEST(LasReader, ReadsKnownPointsExactly_ForEveryVersionAndFormat) {
    for (int minor = 0; minor <= 4; ++minor) {
        for (int format = 0; format <= 10; ++format) {
            if (format >= 6 && minor < 4)
                continue;
            LasTestFile file;
            file.versionMinor = minor;
            file.pointFormat = format;
            file.scale = {0.001, 0.01, 0.25};
            file.offset = {500000.0, 4000000.0, -10.0};
            file.points = samplePoints();
            const PointCloud cloud = readBytes(file.bytes());
            SCOPED_TRACE("LAS 1." + std::to_string(minor) + " format " + std::to_string(format));
            EXPECT_EQ(cloud.kind, InputKind::Las);
            EXPECT_EQ(cloud.recordsRead, 5U);
            EXPECT_EQ(cloud.filteredOut, 1U); // the withheld point
            ASSERT_EQ(cloud.points.size(), 4U);
            for (std::size_t i = 0; i < 4; ++i) {
                const LasTestPoint& p = file.points[i];
                EXPECT_EQ(cloud.points[i].x, p.x * 0.001 + 500000.0);
                EXPECT_EQ(cloud.points[i].y, p.y * 0.01 + 4000000.0);
                EXPECT_EQ(cloud.points[i].z, p.z * 0.25 + -10.0);
            }
            EXPECT_TRUE(cloud.crsWkt.empty());
        }
    }
}

TEST(LasReader, KeepsRequestedClassesAndReturns) {
    for (const int format : {1, 6}) {
        LasTestFile file;
        file.versionMinor = 4;
        file.pointFormat = format;
        file.points = samplePoints();
        const std::vector<std::byte> bytes = file.bytes();

        LasReadOptions ground;
        ground.classes = {2};
        PointCloud cloud = readBytes(bytes, ground);
        ASSERT_EQ(cloud.points.size(), 2U);
        EXPECT_EQ(cloud.points[0].z, 3.0);
        EXPECT_EQ(cloud.points[1].z, 0.12);
        EXPECT_EQ(cloud.filteredOut, 3U);

        LasReadOptions several;
        several.classes = {1, 5};
        EXPECT_EQ(readBytes(bytes, several).points.size(), 2U);

        LasReadOptions first;
        first.returns = LasReturns::First;
        cloud = readBytes(bytes, first);
        ASSERT_EQ(cloud.points.size(), 2U);
        EXPECT_EQ(cloud.points[1].x, -1.0);

        LasReadOptions last;
        last.returns = LasReturns::Last;
        cloud = readBytes(bytes, last);
        ASSERT_EQ(cloud.points.size(), 2U);
        EXPECT_EQ(cloud.points[1].x, 10000.0);

        LasReadOptions lastGround;
        lastGround.returns = LasReturns::Last;
        lastGround.classes = {2};
        EXPECT_EQ(readBytes(bytes, lastGround).points.size(), 2U);
    }
}

TEST(LasReader, ReadsClassesAbove31_InExtendedFormats) {
    LasTestFile file;
    file.versionMinor = 4;
    file.pointFormat = 6;
    file.points = {{0, 0, 0, 1, 1, 40, false}, {1, 0, 0, 1, 1, 2, false}};
    LasReadOptions options;
    options.classes = {40};
    EXPECT_EQ(readBytes(file.bytes(), options).points.size(), 1U);
}

TEST(LasReader, ReadsThroughSeveralBuffers_FromAFile) {
    // 4 MiB buffers of 28-byte records hold 149796 records: 400000 need three reads.
    LasTestFile file;
    file.pointFormat = 1;
    file.scale = {1.0, 1.0, 1.0};
    for (std::int32_t i = 0; i < 400000; ++i)
        file.points.push_back({i, -i, i % 1000, 1, 1, static_cast<std::uint8_t>(i % 2 ? 2 : 1)});
    ScratchFile scratch("big.las");
    scratch.write(file.bytes());
    int calls = 0;
    LasReadOptions options;
    options.classes = {2};
    const PointCloud cloud = readLasPoints(scratch.path(), options, [&](double fraction, auto) {
        ++calls;
        EXPECT_GT(fraction, 0.0);
        EXPECT_LE(fraction, 1.0);
        return true;
    });
    EXPECT_EQ(calls, 3);
    ASSERT_EQ(cloud.points.size(), 200000U);
    for (std::size_t k = 0; k < cloud.points.size(); ++k) {
        const auto i = static_cast<double>(2 * k + 1);
        ASSERT_EQ(cloud.points[k].x, i);
        ASSERT_EQ(cloud.points[k].y, -i);
    }
    EXPECT_EQ(readLasHeader(scratch.path()).pointCount, 400000U);
}

TEST(LasReader, ThrowsCancelled_WhenProgressSaysStop) {
    LasTestFile file;
    file.points = samplePoints();
    EXPECT_THROW(readLasPointsFromMemory(file.bytes(), "x.las", {},
                                         [](double, std::string_view) { return false; }),
                 Cancelled);
}

TEST(LasReader, TakesCrsFromGeoKeys) {
    LasTestFile file;
    file.points = samplePoints();
    file.vlrs.push_back(test::geoKeysForProjectedEpsg(32619));
    const PointCloud cloud = readBytes(file.bytes());
    EXPECT_EQ(crs::describeCrs(cloud.crsWkt).code, "EPSG:32619");
}

TEST(LasReader, PrefersWktRecord_WhenTheWktBitIsSet) {
    LasTestFile file;
    file.versionMinor = 4;
    file.pointFormat = 6;
    file.points = samplePoints();
    file.wktBit = true;
    file.vlrs.push_back(test::geoKeysForProjectedEpsg(32619));
    file.vlrs.push_back(test::wktRecord(crs::crsFromUserInput("EPSG:2992", "test")));
    EXPECT_EQ(crs::describeCrs(readBytes(file.bytes()).crsWkt).code, "EPSG:2992");
    // Without the bit the GeoTIFF keys rule.
    file.wktBit = false;
    EXPECT_EQ(crs::describeCrs(readBytes(file.bytes()).crsWkt).code, "EPSG:32619");
}

TEST(LasReader, TakesCrsFromAnExtendedRecord) {
    LasTestFile file;
    file.versionMinor = 4;
    file.pointFormat = 7;
    file.points = samplePoints();
    file.wktBit = true;
    file.evlrs.push_back(test::wktRecord(crs::crsFromUserInput("EPSG:32633", "test")));
    EXPECT_EQ(crs::describeCrs(readBytes(file.bytes()).crsWkt).code, "EPSG:32633");
}

TEST(LasReader, ThrowsCrsError_ForMalformedGeoKeys) {
    LasTestFile file;
    file.points = samplePoints();
    test::LasTestRecord keys = test::geoKeysForProjectedEpsg(32619);
    poke<std::uint16_t>(keys.data, 6, 40); // claims 40 keys, holds 3
    file.vlrs.push_back(keys);
    EXPECT_THROW(readBytes(file.bytes()), CrsError);

    // Keys GDAL derives no CRS from get a message that names the cause, not GDAL's "unknown
    // GDAL error".
    LasTestFile other;
    other.points = samplePoints();
    other.vlrs.push_back(test::geoKeysForProjectedEpsg(7)); // no CRS has code 7
    try {
        (void)readBytes(other.bytes());
    } catch (const CrsError& error) {
        EXPECT_EQ(std::string(error.what()).find("unknown GDAL error"), std::string::npos)
            << error.what();
    }
}

/// The message of the InvalidInputError `bytes` raise, or "" when they raise none.
std::string rejection(const std::vector<std::byte>& bytes) {
    try {
        readBytes(bytes);
    } catch (const InvalidInputError& error) {
        return error.what();
    }
    return {};
}

TEST(LasReader, RejectsEveryTruncation_WithoutReadingOutOfBounds) {
    LasTestFile file;
    file.versionMinor = 4;
    file.pointFormat = 6;
    file.points = samplePoints();
    file.vlrs.push_back(test::wktRecord("GEOGCS[\"x\"]"));
    const std::vector<std::byte> whole = file.bytes();
    for (std::size_t size = 0; size < whole.size(); ++size) {
        const std::vector<std::byte> cut(whole.begin(),
                                         whole.begin() + static_cast<std::ptrdiff_t>(size));
        EXPECT_NE(rejection(cut), "") << "a file cut to " << size << " bytes was accepted";
    }
}

TEST(LasReader, RejectsLyingHeaders_WithClearMessages) {
    LasTestFile file;
    file.versionMinor = 4;
    file.pointFormat = 6;
    file.points = samplePoints();
    const std::vector<std::byte> good = file.bytes();
    ASSERT_EQ(rejection(good), "");

    struct Lie {
        std::string what;
        std::function<void(std::vector<std::byte>&)> corrupt;
        std::string expected;
    };
    const std::vector<Lie> lies{
        {"signature", [](auto& b) { poke<std::uint8_t>(b, 0, 'X'); }, "no LASF signature"},
        {"version", [](auto& b) { poke<std::uint8_t>(b, 24, 2); }, "version 2.4"},
        {"minor version", [](auto& b) { poke<std::uint8_t>(b, 25, 9); }, "version 1.9"},
        {"header size", [](auto& b) { poke<std::uint16_t>(b, 94, 100); }, "header size 100"},
        {"header past end", [](auto& b) { poke<std::uint16_t>(b, 94, 60000); }, "truncated"},
        {"point offset in header", [](auto& b) { poke<std::uint32_t>(b, 96, 10); }, "inside"},
        {"point offset past end", [](auto& b) { poke<std::uint32_t>(b, 96, 1u << 30); },
         "truncated"},
        {"point count 32-bit", [](auto& b) { poke<std::uint32_t>(b, 107, 6); }, "disagree"},
        {"point count 64-bit",
         [](auto& b) {
             poke<std::uint32_t>(b, 107, 0);
             poke<std::uint64_t>(b, 247, std::uint64_t{1} << 62);
         },
         "truncated or lying header"},
        {"one record too many",
         [](auto& b) {
             poke<std::uint32_t>(b, 107, 6);
             poke<std::uint64_t>(b, 247, 6);
         },
         "room for 5"},
        {"record length", [](auto& b) { poke<std::uint16_t>(b, 105, 20); }, "record length 20"},
        {"format", [](auto& b) { poke<std::uint8_t>(b, 104, 11); }, "format 11"},
        {"LAZ bit", [](auto& b) { poke<std::uint8_t>(b, 104, 6 | 0x80); },
         "marked LASzip-compressed (LAZ), but there is no LASzip record"},
        {"VLR count", [](auto& b) { poke<std::uint32_t>(b, 100, 3); }, "runs into the point data"},
        {"EVLR start",
         [](auto& b) {
             poke<std::uint64_t>(b, 235, 400);
             poke<std::uint32_t>(b, 243, 1);
         },
         "extended variable length records start"},
        {"EVLR count",
         [&](auto& b) {
             poke<std::uint64_t>(b, 235, b.size());
             poke<std::uint32_t>(b, 243, 1);
         },
         "runs past the end"},
        {"zero scale", [](auto& b) { poke<double>(b, 131, 0.0); }, "scale"},
        {"NaN offset",
         [](auto& b) { poke<double>(b, 163, std::numeric_limits<double>::quiet_NaN()); }, "offset"},
    };
    for (const Lie& lie : lies) {
        std::vector<std::byte> bytes = good;
        lie.corrupt(bytes);
        const std::string message = rejection(bytes);
        EXPECT_NE(message.find(lie.expected), std::string::npos)
            << lie.what << ": got '" << message << "'";
        EXPECT_NE(message.find("test.las"), std::string::npos) << lie.what;
    }
}

// Whether records are compressed is the format byte's to say, not the name's: an
// uncompressed file named .LAZ reads as LAS, and so does one with a LASzip record left
// behind by a tool that decompressed the points.
TEST(LasReader, ReadsUncompressedRecords_WhateverTheNameOrAStaleLaszipRecord) {
    LasTestFile file;
    file.points = samplePoints();
    const std::size_t expected = readBytes(file.bytes()).points.size();
    ASSERT_GT(expected, 0U);
    EXPECT_EQ(readLasPointsFromMemory(file.bytes(), "cloud.LAZ").points.size(), expected);
    file.vlrs.push_back({"laszip encoded", 22204, std::vector<std::byte>(34)});
    EXPECT_EQ(readBytes(file.bytes()).points.size(), expected);
}

// The compression mark with a LASzip record that is no valid one: the LAZ reader's error.
TEST(LasReader, ReportsAMalformedLaszipRecord_OfACompressedFile) {
    LasTestFile file;
    file.points = samplePoints();
    file.vlrs.push_back({"laszip encoded", 22204, std::vector<std::byte>(10)});
    std::vector<std::byte> bytes = file.bytes();
    poke<std::uint8_t>(bytes, 104, std::to_integer<std::uint8_t>(bytes[104]) | 0x80);
    const std::string message = rejection(bytes);
    EXPECT_NE(message.find("LazReader"), std::string::npos) << message;
    EXPECT_NE(message.find("test.las"), std::string::npos) << message;
}

// Point format 99 (bits 6, 5, 1 and 0) is an unknown format, not LAZ: bit 6 alone is no
// LASzip mark, since LASzip always sets bit 7 too.
TEST(LasReader, ReportsAnUnknownPointFormat_NotLaz) {
    LasTestFile file;
    file.points = samplePoints();
    std::vector<std::byte> bytes = file.bytes();
    for (const std::uint8_t format : {std::uint8_t{99}, std::uint8_t{64 | 6}}) {
        poke<std::uint8_t>(bytes, 104, format);
        const std::string message = rejection(bytes);
        EXPECT_NE(message.find("point data record format " + std::to_string(format) +
                               " is not supported"),
                  std::string::npos)
            << message;
        EXPECT_EQ(message.find("LAZ"), std::string::npos) << message;
    }
    // LASzip's own marks stay LAZ: bit 7 (formats 0-5), bits 7 and 6 (formats 6-10, here
    // only set on this format-1 file); it has no LASzip record to decode them with.
    for (const std::uint8_t format : {std::uint8_t{0x80 | 1}, std::uint8_t{0xC0 | 1}}) {
        poke<std::uint8_t>(bytes, 104, format);
        const std::string message = rejection(bytes);
        EXPECT_NE(message.find("marked LASzip-compressed (LAZ)"), std::string::npos) << message;
    }
}

TEST(LasReader, ThrowsIoError_ForAMissingFile) {
    EXPECT_THROW(readLasPoints("/no/such/file.las"), IoError);
}

TEST(LasReader, RejectsClassesOutsideAByte) {
    LasTestFile file;
    file.points = samplePoints();
    LasReadOptions options;
    options.classes = {256};
    EXPECT_THROW(readBytes(file.bytes(), options), InvalidInputError);
}

// The shared LAS files: every point record read, the points inside the header's bounds and
// reaching them (the bounds are the extremes of the stored points), the CRS as documented.
struct SharedLas {
    std::string name;
    std::uint64_t points;
    std::uint64_t ground;
    std::string crsFragment; // in the CRS name, "" when the file has none
};

class SharedLasFiles : public ::testing::TestWithParam<SharedLas> {};

TEST_P(SharedLasFiles, MatchHeaderCountsBoundsAndGroundCount) {
    const SharedLas& expected = GetParam();
    const fs::path path = sharedFile(expected.name);
    if (!fs::exists(path))
        GTEST_SKIP() << path << " not available";
    const LasHeader header = readLasHeader(path.string());
    const PointCloud cloud = readLasPoints(path.string());
    EXPECT_EQ(header.pointCount, expected.points);
    EXPECT_EQ(cloud.recordsRead, header.pointCount);
    EXPECT_EQ(cloud.points.size(), header.pointCount);
    EXPECT_EQ(cloud.filteredOut, 0U);

    std::array<double, 6> bounds{
        std::numeric_limits<double>::infinity(),  std::numeric_limits<double>::infinity(),
        std::numeric_limits<double>::infinity(),  -std::numeric_limits<double>::infinity(),
        -std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()};
    for (const Point3& p : cloud.points) {
        const double xyz[3] = {p.x, p.y, p.z};
        for (std::size_t a = 0; a < 3; ++a) {
            bounds[a] = std::min(bounds[a], xyz[a]);
            bounds[a + 3] = std::max(bounds[a + 3], xyz[a]);
        }
    }
    for (std::size_t a = 0; a < 6; ++a) // the header stores rounded bounds: half a unit step
        EXPECT_NEAR(bounds[a], header.bounds[a], header.scale[a % 3]) << "bound " << a;

    LasReadOptions ground;
    ground.classes = {2};
    const PointCloud groundCloud = readLasPoints(path.string(), ground);
    EXPECT_EQ(groundCloud.points.size(), expected.ground);
    EXPECT_EQ(groundCloud.points.size() + groundCloud.filteredOut, expected.points);

    const crs::CrsDescription description = crs::describeCrs(cloud.crsWkt);
    if (expected.crsFragment.empty()) {
        EXPECT_TRUE(cloud.crsWkt.empty());
    } else {
        EXPECT_NE(description.name.find(expected.crsFragment), std::string::npos)
            << description.name;
    }
}

INSTANTIATE_TEST_SUITE_P(
    SharedDems, SharedLasFiles,
    ::testing::Values(SharedLas{"pdal__autzen_trim.las", 110000, 26107, "Lambert"},
                      SharedLas{"pdal__autzen_trim_7.las", 110000, 26107, "Lambert"},
                      SharedLas{"pdal__hexbin-crop.las", 38367, 35318, "UTM zone 42N"},
                      SharedLas{"pdal__1.2-with-color.las", 1065, 276, ""},
                      SharedLas{"pdal__test1_4.las", 1000, 1000, "New Mexico Central"}),
    [](const auto& testInfo) {
        std::string name = testInfo.param.name;
        std::replace_if(
            name.begin(), name.end(), [](char c) { return !std::isalnum(c); }, '_');
        return name;
    });

TEST(LasReader, AutzenGeoKeysAndWktGiveTheSameOregonLambertFeet) {
    const fs::path keys = sharedFile("pdal__autzen_trim.las");  // 1.2: GeoTIFF keys rule
    const fs::path wkt = sharedFile("pdal__autzen_trim_7.las"); // 1.4: WKT
    if (!fs::exists(keys) || !fs::exists(wkt))
        GTEST_SKIP() << "autzen files not available";
    const PointCloud a = readLasPoints(keys.string());
    const PointCloud b = readLasPoints(wkt.string());
    const crs::CrsDescription da = crs::describeCrs(a.crsWkt);
    const crs::CrsDescription db = crs::describeCrs(b.crsWkt);
    EXPECT_TRUE(da.projected);
    EXPECT_NEAR(da.metresPerUnit, 0.3048, 1e-6) << da.linearUnit;
    EXPECT_NEAR(db.metresPerUnit, 0.3048, 1e-6) << db.linearUnit;
    // Same points, same place: one transformation between the two CRSs moves nothing.
    const crs::Reprojector reprojector(a.crsWkt, b.crsWkt);
    const Point2 moved = reprojector.transform(Point2{a.points[0].x, a.points[0].y});
    EXPECT_NEAR(moved.x, a.points[0].x, 0.01);
    EXPECT_NEAR(moved.y, a.points[0].y, 0.01);
    ASSERT_EQ(a.points.size(), b.points.size());
    EXPECT_EQ(a.points, b.points);
}

} // namespace
} // namespace terratin::io

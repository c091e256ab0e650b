// Tests of the layered LAZ compressor (3, LAS 1.4 point formats 6-10) on real files. Only one
// layered file has a same-format twin (laz_decode_test compares it byte for byte); the others
// are checked against files of the same points in another format (COPC copies, LAS 1.2
// originals) as sorted point sets, against their own headers (bounds, 64-bit counts by return,
// chunk sizes), and against themselves: the TIN fields alone, piece by piece, damaged. The
// files are read in place from TERRATIN_SHARED_DEMS/laz; a test skips itself when they are
// absent.

#include "laz_test_files.hpp"

#include "chunk_decoder.hpp"
#include "laz_file.hpp"
#include "terratin/error.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <compare>
#include <optional>
#include <random>
#include <string>
#include <vector>

namespace terratin::io::laz {
namespace {

using test::decodeAll;
using test::fileBytes;
using test::sharedLaz;

/// Every layered file of the shared set.
constexpr std::array kLayeredFiles{
    "laspy__1_4_w_evlr.laz",     "rlas__example.copc.laz",
    "laspy__simple.copc.laz",    "laspy__simple_with_page.copc.laz",
    "copcjs__ellipsoid-1.4.laz", "copcjs__ellipsoid.copc.laz",
    "pdal__lone-star.copc.laz",  "untwine__eb.laz",
    "laspy__append-bug.laz",     "pdal__las_with_several_extra_byte_bloc.laz",
    "laspy__fullwave.laz"};

std::optional<LazFile> openShared(const std::string& name) {
    const auto path = sharedLaz(name);
    if (!std::filesystem::exists(path))
        return std::nullopt;
    return LazFile::open(path.string());
}

/// Scale, offset and bounds of a LAS header (LAS 1.4 R15 table 3), per axis x, y, z.
struct Geometry {
    std::array<double, 3> scale{}, offset{}, low{}, high{};
};

Geometry geometry(std::span<const std::byte> header) {
    Geometry g;
    for (std::size_t axis = 0; axis < 3; ++axis) {
        g.scale[axis] = loadLe<double>(header.data() + 131 + 8 * axis);
        g.offset[axis] = loadLe<double>(header.data() + 155 + 8 * axis);
        g.high[axis] = loadLe<double>(header.data() + 179 + 16 * axis);
        g.low[axis] = loadLe<double>(header.data() + 187 + 16 * axis);
    }
    return g;
}

/// The fields every point format has, comparable across formats and scales: coordinates in
/// steps of a common grid, the scan angle in whole degrees (formats 6-10 store 0.006° steps).
struct CommonFields {
    std::array<std::int64_t, 3> xyz{};
    unsigned intensity = 0, returnNumber = 0, returnCount = 0, classification = 0;
    unsigned scanDirection = 0, edge = 0, userData = 0, sourceId = 0;
    long scanAngleDegrees = 0;
    double gpsTime = 0;
    std::array<unsigned, 3> rgb{};
    auto operator<=>(const CommonFields&) const = default;
};

unsigned byteAt(const std::byte* record, std::size_t at) {
    return std::to_integer<unsigned>(record[at]);
}

void readLas14Fields(const std::byte* r, int format, CommonFields& f) {
    f.returnNumber = byteAt(r, 14) & 15u;
    f.returnCount = byteAt(r, 14) >> 4;
    f.scanDirection = (byteAt(r, 15) >> 6) & 1u;
    f.edge = byteAt(r, 15) >> 7;
    f.classification = byteAt(r, 16);
    f.userData = byteAt(r, 17);
    f.scanAngleDegrees = std::lround(0.006 * loadLe<std::int16_t>(r + 18));
    f.sourceId = loadLe<std::uint16_t>(r + 20);
    f.gpsTime = loadLe<double>(r + 22);
    if (format == 7 || format == 8 || format == 10)
        for (std::size_t c = 0; c < 3; ++c)
            f.rgb[c] = loadLe<std::uint16_t>(r + 30 + 2 * c);
}

void readLas12Fields(const std::byte* r, int format, CommonFields& f) {
    f.returnNumber = byteAt(r, 14) & 7u;
    f.returnCount = (byteAt(r, 14) >> 3) & 7u;
    f.scanDirection = (byteAt(r, 14) >> 6) & 1u;
    f.edge = byteAt(r, 14) >> 7;
    f.classification = byteAt(r, 15) & 31u;
    f.scanAngleDegrees = loadLe<std::int8_t>(r + 16);
    f.userData = byteAt(r, 17);
    f.sourceId = loadLe<std::uint16_t>(r + 18);
    const bool time = format == 1 || format == 3 || format == 4 || format == 5;
    if (time)
        f.gpsTime = loadLe<double>(r + 20);
    if (format == 2 || format == 3 || format == 5)
        for (std::size_t c = 0; c < 3; ++c)
            f.rgb[c] = loadLe<std::uint16_t>(r + (time ? 28 : 20) + 2 * c);
}

/// The common fields of every record; coordinates in steps of `grid` (metres, the scale both
/// files' coordinates are multiples of).
std::vector<CommonFields> commonFields(const std::vector<std::byte>& records, std::size_t length,
                                       int format, const Geometry& g, double grid) {
    std::vector<CommonFields> points;
    for (std::size_t at = 0; at < records.size(); at += length) {
        const std::byte* r = records.data() + at;
        CommonFields f;
        for (std::size_t axis = 0; axis < 3; ++axis) {
            const double value =
                loadLe<std::int32_t>(r + 4 * axis) * g.scale[axis] + g.offset[axis];
            f.xyz[axis] = std::llround(value / grid);
        }
        f.intensity = loadLe<std::uint16_t>(r + 12);
        if (format >= 6)
            readLas14Fields(r, format, f);
        else
            readLas12Fields(r, format, f);
        points.push_back(f);
    }
    return points;
}

/// A decoded file as common fields.
struct DecodedPoints {
    std::vector<CommonFields> points;
    Geometry geometry;
};

DecodedPoints decodeShared(const LazFile& file, double grid) {
    std::array<std::byte, 227> header{};
    file.readBytes(0, header);
    const Geometry g = geometry(header);
    return {commonFields(decodeAll(file), file.header().recordLength, file.header().pointFormat, g,
                         grid),
            g};
}

std::vector<CommonFields> lasTwinPoints(const std::string& name, double grid) {
    const std::vector<std::byte> bytes = fileBytes(sharedLaz(name));
    const test::LasRecords twin = test::lasRecords(sharedLaz(name));
    return commonFields(twin.bytes, twin.recordLength, twin.pointFormat,
                        geometry(std::span(bytes).first(227)), grid);
}

/// A layered file and a file of the same points in another format (a LAS twin or a
/// pointwise LAZ), compared as sorted point sets, since COPC stores points in octree order.
struct SamePoints {
    const char* layered;
    const char* other;
    /// The common grid of both files' coordinates (metres).
    double grid;
};

void PrintTo(const SamePoints& pair, std::ostream* out) {
    *out << pair.layered;
}

class LazLayeredSamePointsTest : public ::testing::TestWithParam<SamePoints> {};

TEST_P(LazLayeredSamePointsTest, HoldsTheSamePointsAsTheOtherFormat) {
    const SamePoints pair = GetParam();
    const std::optional<LazFile> layered = openShared(pair.layered);
    if (!layered || !std::filesystem::exists(sharedLaz(pair.other)))
        GTEST_SKIP() << "shared LAZ test files absent";
    std::vector<CommonFields> mine = decodeShared(*layered, pair.grid).points;
    std::vector<CommonFields> theirs;
    if (std::string(pair.other).ends_with(".las"))
        theirs = lasTwinPoints(pair.other, pair.grid);
    else
        theirs = decodeShared(LazFile::open(sharedLaz(pair.other).string()), pair.grid).points;
    ASSERT_EQ(mine.size(), theirs.size());
    std::sort(mine.begin(), mine.end());
    std::sort(theirs.begin(), theirs.end());
    const auto [a, b] = std::mismatch(mine.begin(), mine.end(), theirs.begin());
    EXPECT_TRUE(a == mine.end()) << pair.layered << ": sorted point " << (a - mine.begin())
                                 << " differs from " << pair.other;
}

// pdal__lone-star.copc's header bounds differ from the original's by up to 0.00225, which
// looked like requantization; the points themselves lie on the same 0.00025 grid and are
// equal exactly, with their intensities, returns and classes.
INSTANTIATE_TEST_SUITE_P(
    SharedFiles, LazLayeredSamePointsTest,
    ::testing::Values(SamePoints{"laspy__simple.copc.laz", "laspy__simple.las", 0.01},
                      SamePoints{"laspy__simple_with_page.copc.laz", "laspy__simple.las", 0.01},
                      SamePoints{"copcjs__ellipsoid.copc.laz", "copcjs__ellipsoid.laz", 0.01},
                      SamePoints{"pdal__lone-star.copc.laz", "pdal__lone-star.laz", 0.00025},
                      SamePoints{"rlas__example.copc.laz", "rlas__example.las", 0.001}));

TEST(LazLayered, Ellipsoid14KeepsThePointwiseFilesPointsAndRescalesColours) {
    // The same points in the same order as the LAS 1.2 original, colours widened from 8 to 16
    // bits (x 257) by the converter that wrote it, intensities rescaled (128 became 32767,
    // 255 became 65535), so intensity is left out.
    const std::optional<LazFile> layered = openShared("copcjs__ellipsoid-1.4.laz");
    const std::optional<LazFile> original = openShared("copcjs__ellipsoid.laz");
    if (!layered || !original)
        GTEST_SKIP() << "shared LAZ test files absent";
    std::vector<CommonFields> mine = decodeShared(*layered, 0.01).points;
    std::vector<CommonFields> theirs = decodeShared(*original, 0.01).points;
    ASSERT_EQ(mine.size(), theirs.size());
    for (std::size_t i = 0; i < mine.size(); ++i) {
        for (unsigned& c : theirs[i].rgb)
            c *= 257;
        theirs[i].intensity = mine[i].intensity;
        ASSERT_TRUE(mine[i] == theirs[i]) << "point " << i;
    }
}

class LazLayeredFileTest : public ::testing::TestWithParam<const char*> {};

TEST_P(LazLayeredFileTest, DecodedPointsAgreeWithTheirHeader) {
    // Inside the header's bounds (within half a scale step), and the LAS 1.4 header's 64-bit
    // points by return (15 of them, byte 255 on) counted from the 4-bit return numbers;
    // decodeAll checks that every chunk used exactly its chunk-table byte count.
    const std::optional<LazFile> file = openShared(GetParam());
    if (!file)
        GTEST_SKIP() << "shared LAZ test files absent";
    std::array<std::byte, 375> header{};
    file->readBytes(0, header);
    const Geometry g = geometry(header);
    const std::vector<std::byte> records = decodeAll(*file);
    const std::size_t length = file->header().recordLength;
    std::array<std::uint64_t, 15> byReturn{};
    for (std::size_t at = 0; at < records.size(); at += length) {
        for (std::size_t axis = 0; axis < 3; ++axis) {
            const double value =
                loadLe<std::int32_t>(records.data() + at + 4 * axis) * g.scale[axis] +
                g.offset[axis];
            ASSERT_TRUE(value >= g.low[axis] - g.scale[axis] / 2 &&
                        value <= g.high[axis] + g.scale[axis] / 2)
                << GetParam() << ": point " << at / length << " outside the header's bounds";
        }
        const unsigned returnNumber = std::to_integer<unsigned>(records[at + 14]) & 15u;
        if (returnNumber >= 1)
            ++byReturn[returnNumber - 1];
    }
    for (std::size_t r = 0; r < byReturn.size(); ++r)
        EXPECT_EQ(byReturn[r], loadLe<std::uint64_t>(header.data() + 255 + 8 * r))
            << GetParam() << ": points of return " << r + 1;
}

TEST_P(LazLayeredFileTest, TinFieldsAgreeWithEveryField) {
    // x, y, z (bytes 0-11), the return byte (14), the flag byte (15) and classification
    // (16) as when every field is decoded; every other byte as in the chunk's first record.
    const std::optional<LazFile> file = openShared(GetParam());
    if (!file)
        GTEST_SKIP() << "shared LAZ test files absent";
    const std::vector<std::byte> every = decodeAll(*file);
    const std::vector<std::byte> tin = decodeAll(*file, FieldSelection::TinFields);
    ASSERT_EQ(tin.size(), every.size());
    const std::size_t length = file->header().recordLength;
    for (const LazChunk& chunk : file->chunks()) {
        const std::byte* first = every.data() + chunk.firstPoint * length;
        for (std::uint64_t p = chunk.firstPoint; p < chunk.firstPoint + chunk.pointCount; ++p) {
            for (std::size_t b = 0; b < length; ++b) {
                const bool tinByte = b < 12 || (b >= 14 && b <= 16);
                const std::byte expected = tinByte ? every[p * length + b] : first[b];
                ASSERT_EQ(tin[p * length + b], expected)
                    << GetParam() << ": point " << p << ", "
                    << test::fieldAt(file->header().pointFormat, b);
            }
        }
    }
}

INSTANTIATE_TEST_SUITE_P(SharedFiles, LazLayeredFileTest, ::testing::ValuesIn(kLayeredFiles));

TEST(LazLayeredChunk, DecodesPieceByPieceAsAtOnce) {
    for (const FieldSelection fields : {FieldSelection::Every, FieldSelection::TinFields}) {
        for (const char* name :
             {"pdal__las_with_several_extra_byte_bloc.laz", "laspy__fullwave.laz"}) {
            const std::optional<LazFile> file = openShared(name);
            if (!file)
                GTEST_SKIP() << "shared LAZ test files absent";
            const std::size_t index = file->chunks().size() > 3 ? 3 : 0;
            std::vector<std::byte> bytes;
            file->readChunk(index, bytes);
            const LazChunk& chunk = file->chunks()[index];
            const std::size_t length = file->header().recordLength;
            ChunkDecoder decoder(file->laszip(), file->name(), fields);
            std::vector<std::byte> whole(chunk.pointCount * length);
            decoder.decode(bytes, chunk.pointCount, whole, "whole");
            std::vector<std::byte> pieces(whole.size());
            decoder.begin(bytes, chunk.pointCount, "pieces");
            std::size_t done = 0;
            for (const std::size_t piece : {1, 2, 997, 4000, 1}) {
                decoder.decodeNext(std::span(pieces).subspan(done * length, piece * length));
                done += piece;
            }
            decoder.decodeNext(std::span(pieces).subspan(done * length));
            EXPECT_EQ(decoder.pointsLeft(), 0u);
            EXPECT_EQ(decoder.bytesUsed(), chunk.byteCount) << name;
            EXPECT_TRUE(pieces == whole) << name;
        }
    }
}

} // namespace
} // namespace terratin::io::laz

// Tests of the LAZ decoder on real files: each LAZ with an uncompressed twin decodes to
// exactly the twin's point-record bytes (every byte of every record compared; a mismatch
// names the first point and field), each chunk uses exactly the bytes its table entry
// gives, and damaged chunks fail with a clear error instead of crashing. The files are read
// in place from TERRATIN_SHARED_DEMS/laz; a test skips itself when they are absent.

#include "laz_test_files.hpp"

#include "chunk_decoder.hpp"
#include "laz_file.hpp"
#include "terratin/error.hpp"

#include <gtest/gtest.h>

#include <array>
#include <optional>
#include <random>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

namespace terratin::io::laz {
namespace {

using test::decodeAll;
using test::firstDifference;
using test::lasRecords;
using test::sharedDem;
using test::sharedLaz;

/// The shared file `name` or nothing when the files are absent.
std::optional<LazFile> openShared(const char* name) {
    const auto path = sharedLaz(name);
    if (!std::filesystem::exists(path))
        return std::nullopt;
    return LazFile::open(path.string());
}

struct TwinPair {
    const char* laz;
    const char* las; ///< relative to the laz folder
    const char* covers;
};

void PrintTo(const TwinPair& pair, std::ostream* out) {
    *out << pair.laz;
}

class LazTwinTest : public ::testing::TestWithParam<TwinPair> {};

TEST_P(LazTwinTest, DecodesToTheTwinsRecordBytes) {
    const TwinPair pair = GetParam();
    const auto lazPath = sharedLaz(pair.laz);
    const auto lasPath = sharedLaz(pair.las);
    if (!std::filesystem::exists(lazPath) || !std::filesystem::exists(lasPath))
        GTEST_SKIP() << "shared LAZ test files absent: " << lazPath;
    const LazFile file = LazFile::open(lazPath.string());
    const test::LasRecords twin = lasRecords(lasPath);
    ASSERT_EQ(file.header().pointCount, twin.count);
    ASSERT_EQ(file.header().recordLength, twin.recordLength);
    const std::vector<std::byte> decoded = decodeAll(file);
    const auto difference =
        firstDifference(decoded, twin.bytes, twin.recordLength, twin.pointFormat);
    EXPECT_FALSE(difference) << pair.laz << " (" << pair.covers << "): " << *difference;
}

INSTANTIATE_TEST_SUITE_P(
    SharedFiles, LazTwinTest,
    ::testing::Values(
        TwinPair{"lazrs__point10.laz", "lazrs__point10.las", "POINT10 v2"},
        TwinPair{"lazrs__point-time.laz", "lazrs__point-time.las", "POINT10 + GPSTIME11 v2"},
        TwinPair{"lazrs__point-color.laz", "lazrs__point-color.las", "POINT10 + RGB12 v2"},
        TwinPair{"lazrs__point-time-color.laz", "lazrs__point-time-color.las",
                 "POINT10 + GPSTIME11 + RGB12 v2"},
        TwinPair{"lazrs__extra-bytes.laz", "lazrs__extra-bytes.las", "BYTE v2, 27 bytes"},
        TwinPair{"laspy__simple.laz", "laspy__simple.las", "LASzip 2.3 writer"},
        TwinPair{"laspy__extra.laz", "laspy__extrabytes.las", "LAS 1.4 header, BYTE v2"},
        TwinPair{"pdal__laszip-generated.laz", "../pdal__1.2-with-color.las",
                 "LASzip 2.0r1, padding before the points"},
        TwinPair{"pdal__liblas-generated.laz", "../pdal__1.2-with-color.las", "libLAS writer"},
        TwinPair{"pdal__autzen_trim.laz", "../pdal__autzen_trim.las", "3 chunks"},
        TwinPair{"lazperf__1815.laz", "lazperf__1815.las", "LASzip 3.0r2, fine scale"},
        TwinPair{"lazperf__point10-1.0.laz", "lazperf__point10-1.0.las", "1 point, LAS 1.0"},
        TwinPair{"lazperf__no-points-1.3.laz", "lazperf__no-points-1.3.las", "0 points"},
        TwinPair{"lidr__Megaplot.laz", "lasr__Megaplot.las", "2 chunks"},
        TwinPair{"lidr__Topography.laz", "lasr__Topography.las", "2 chunks"},
        TwinPair{"lidr__MixedConifer.laz", "lasr__MixedConifer.las", "BYTE v2, 8 bytes"},
        TwinPair{"rlas__extra_byte.laz", "rlas__extra_byte.las", "BYTE v2, 4 bytes"},
        TwinPair{"rlas__example.laz", "rlas__example.las", "padding, LASzip VLR not last"},
        TwinPair{"pdal__simple-laszip-compressor-version-1.2r0.laz", "laspy__simple.las",
                 "compressor 1, items version 1"},
        TwinPair{"laspy__1_4_w_evlr.laz", "laspy__1_4_w_evlr.las",
                 "layered compressor, POINT14 version 3"}));

struct HeaderCheck {
    const char* laz;
    /// Whether the header's points by return describe this file (rlas__fwf's were left
    /// from the file it was cut from).
    bool returnsCounted;
};

void PrintTo(const HeaderCheck& check, std::ostream* out) {
    *out << check.laz;
}

/// Files without a twin: every point inside the header's bounds, and the header's points by
/// return (LAS 1.4 R15 table 3) equal to the decoded return numbers' counts.
class LazHeaderCheckTest : public ::testing::TestWithParam<HeaderCheck> {};

TEST_P(LazHeaderCheckTest, DecodedPointsAgreeWithTheirHeader) {
    const char* name = GetParam().laz;
    const auto path = sharedLaz(name);
    if (!std::filesystem::exists(path))
        GTEST_SKIP() << "shared LAZ test files absent: " << path;
    const LazFile file = LazFile::open(path.string());
    const std::vector<std::byte> records = decodeAll(file);
    std::array<std::byte, 227> header{};
    file.readBytes(0, header);
    std::array<std::uint64_t, 5> byReturn{};
    std::array<double, 3> low{}, high{};
    for (std::size_t axis = 0; axis < 3; ++axis) {
        const double scale = loadLe<double>(header.data() + 131 + 8 * axis);
        const double offset = loadLe<double>(header.data() + 155 + 8 * axis);
        high[axis] = (loadLe<double>(header.data() + 179 + 16 * axis) - offset) / scale + 0.5;
        low[axis] = (loadLe<double>(header.data() + 187 + 16 * axis) - offset) / scale - 0.5;
    }
    const std::size_t length = file.header().recordLength;
    for (std::size_t at = 0; at < records.size(); at += length) {
        for (std::size_t axis = 0; axis < 3; ++axis) {
            const double value = loadLe<std::int32_t>(records.data() + at + 4 * axis);
            ASSERT_TRUE(value >= low[axis] && value <= high[axis])
                << name << ": point " << at / length << " outside the header's bounds";
        }
        const unsigned returnNumber = std::to_integer<unsigned>(records[at + 14]) & 7u;
        if (returnNumber >= 1 && returnNumber <= 5)
            ++byReturn[returnNumber - 1];
    }
    for (std::size_t r = 0; r < 5 && GetParam().returnsCounted; ++r)
        EXPECT_EQ(byReturn[r], loadLe<std::uint32_t>(header.data() + 111 + 4 * r))
            << name << ": points of return " << r + 1;
}

INSTANTIATE_TEST_SUITE_P(SharedFiles, LazHeaderCheckTest,
                         ::testing::Values(HeaderCheck{"lastools__TO_core_last_zoom.laz", true},
                                           HeaderCheck{"lastools__fusa.laz", true},
                                           HeaderCheck{"pdal__lone-star.laz", true},
                                           HeaderCheck{"copcjs__ellipsoid.laz", true},
                                           HeaderCheck{"lidr__dbh.laz", true},
                                           HeaderCheck{"rlas__fwf.laz", false}));

TEST(LazWavePackets, EachWaveformFollowsThePreviousOrIsShared) {
    // No twin for the one file with wave packets: the waveforms lie back to back in the
    // external .wdp file, so a packet starts where the last one ended, or at the same place
    // for another return of the same pulse; every packet uses descriptor 1.
    const std::optional<LazFile> file = openShared("rlas__fwf.laz");
    if (!file)
        GTEST_SKIP() << "shared LAZ test files absent";
    const std::vector<std::byte> records = decodeAll(*file);
    const std::size_t length = file->header().recordLength;
    ASSERT_EQ(length, 57u);
    for (std::size_t at = 28; at < records.size(); at += length) {
        ASSERT_EQ(std::to_integer<int>(records[at]), 1) << "point " << at / length;
        if (at < length)
            continue;
        const auto offset = loadLe<std::uint64_t>(records.data() + at + 1);
        const auto lastOffset = loadLe<std::uint64_t>(records.data() + at - length + 1);
        const auto lastSize = loadLe<std::uint32_t>(records.data() + at - length + 9);
        ASSERT_TRUE(offset == lastOffset || offset == lastOffset + lastSize)
            << "point " << at / length;
    }
}

TEST(LazChunkDecoder, ChunksDecodeIndependentlyOnThreads) {
    // Each chunk on its own thread with its own decoder, the last started first: the same
    // records as the twin, since no state passes from one chunk to the next.
    const std::optional<LazFile> file = openShared("pdal__autzen_trim.laz");
    const auto twinPath = sharedDem("pdal__autzen_trim.las");
    if (!file || !std::filesystem::exists(twinPath))
        GTEST_SKIP() << "shared LAZ test files absent";
    const std::size_t length = file->header().recordLength;
    std::vector<std::byte> records(file->header().pointCount * length);
    std::vector<std::thread> threads;
    for (std::size_t i = file->chunks().size(); i-- > 0;) {
        threads.emplace_back([&, i] {
            const LazChunk& chunk = file->chunks()[i];
            std::vector<std::byte> bytes;
            file->readChunk(i, bytes);
            ChunkDecoder decoder(file->laszip(), file->name());
            decoder.decode(
                bytes, chunk.pointCount,
                std::span(records).subspan(chunk.firstPoint * length, chunk.pointCount * length),
                file->chunkLabel(i));
        });
    }
    for (std::thread& thread : threads)
        thread.join();
    const test::LasRecords twin = lasRecords(twinPath);
    const auto difference = firstDifference(records, twin.bytes, length, twin.pointFormat);
    EXPECT_FALSE(difference) << *difference;
}

TEST(LazChunkDecoder, DecodesAChunkPieceByPieceAsAtOnce) {
    const std::optional<LazFile> file = openShared("pdal__autzen_trim.laz");
    if (!file)
        GTEST_SKIP() << "shared LAZ test files absent";
    std::vector<std::byte> bytes;
    file->readChunk(2, bytes);
    const LazChunk& chunk = file->chunks()[2];
    const std::size_t length = file->header().recordLength;
    ChunkDecoder decoder(file->laszip(), file->name());
    std::vector<std::byte> whole(chunk.pointCount * length);
    decoder.decode(bytes, chunk.pointCount, whole, "whole");
    std::vector<std::byte> pieces(whole.size());
    decoder.begin(bytes, chunk.pointCount, "pieces");
    std::size_t done = 0;
    for (const std::size_t piece : {1, 2, 997, 4000}) {
        decoder.decodeNext(std::span(pieces).subspan(done * length, piece * length));
        done += piece;
    }
    decoder.decodeNext(std::span(pieces).subspan(done * length));
    EXPECT_EQ(decoder.pointsLeft(), 0u);
    EXPECT_EQ(decoder.bytesUsed(), chunk.byteCount);
    EXPECT_EQ(pieces, whole);
    EXPECT_THROW(decoder.decodeNext(std::span(pieces).first(length)), std::invalid_argument);
}

TEST(LazChunkDecoder, TruncatedChunksAreClearErrors) {
    const std::optional<LazFile> file = openShared("lazrs__point-time-color.laz");
    if (!file)
        GTEST_SKIP() << "shared LAZ test files absent";
    std::vector<std::byte> bytes;
    file->readChunk(0, bytes);
    const std::uint64_t points = file->chunks()[0].pointCount;
    std::vector<std::byte> records(points * file->header().recordLength);
    ChunkDecoder decoder(file->laszip(), file->name());
    for (const std::size_t kept :
         {std::size_t{0}, std::size_t{20}, std::size_t{40}, bytes.size() - 1}) {
        const std::span<const std::byte> cut(bytes.data(), kept);
        try {
            decoder.decode(cut, points, records, file->chunkLabel(0));
            ADD_FAILURE() << "a chunk cut to " << kept << " bytes decoded";
        } catch (const InvalidInputError& error) {
            EXPECT_NE(std::string(error.what()).find("chunk 1 of 1 is truncated or corrupt"),
                      std::string::npos)
                << error.what();
        }
    }
}

TEST(LazChunkDecoder, DamagedChunksNeverReadOutsideTheirBytes) {
    // Random bytes changed: the decoder either notices (InvalidInputError) or yields other
    // points, but stays inside the chunk (checked by the sanitizers in the dev build).
    const std::optional<LazFile> file = openShared("lazrs__extra-bytes.laz");
    if (!file)
        GTEST_SKIP() << "shared LAZ test files absent";
    std::vector<std::byte> good;
    file->readChunk(0, good);
    const std::uint64_t points = file->chunks()[0].pointCount;
    std::vector<std::byte> records(points * file->header().recordLength);
    ChunkDecoder decoder(file->laszip(), file->name());
    std::mt19937 random(11);
    int noticed = 0;
    for (int trial = 0; trial < 200; ++trial) {
        std::vector<std::byte> bytes = good;
        for (int flips = 0; flips < 1 + trial % 8; ++flips)
            bytes[random() % bytes.size()] = static_cast<std::byte>(random());
        try {
            decoder.decode(bytes, points, records, "damaged chunk");
        } catch (const InvalidInputError&) {
            ++noticed;
        }
    }
    EXPECT_GT(noticed, 0);
}

} // namespace
} // namespace terratin::io::laz

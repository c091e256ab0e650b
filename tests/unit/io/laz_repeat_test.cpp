// Tests of terratin-lazrepeat (tools/lazrepeat/laz_repeat.hpp) on the shared LAZ files: a file
// repeated 3 times opens as LAZ with 3 x the points and chunks, its chunks are the input's
// bytes, it decodes (LazFile + ChunkDecoder, and the public readLasPoints) to the input's
// points three times over, and its LAS twin reads to the same points and records. The LAS 1.4
// layered files (compressor 3) are checked as containers when the decoder cannot decode them
// yet. The files are read in place from TERRATIN_SHARED_DEMS; a test skips itself when they
// are absent.

#include "laz_file.hpp"
#include "laz_repeat.hpp"
#include "laz_test_files.hpp"
#include "temporary_directory.hpp"
#include "terratin/error.hpp"
#include "terratin/io/las_reader.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <optional>
#include <set>
#include <string>
#include <vector>

namespace terratin::lazrepeat {
namespace {

namespace fs = std::filesystem;
using io::laz::LazFile;
using io::laz::test::sharedLaz;

constexpr std::uint32_t kCopies = 3;

#define SKIP_WITHOUT(path)                                                                         \
    if (!fs::exists(path))                                                                         \
    GTEST_SKIP() << (path) << " is absent"

RepeatRequest request(const fs::path& input, const fs::path& output,
                      std::optional<fs::path> twin = std::nullopt) {
    RepeatRequest r;
    r.input = input;
    r.output = output;
    r.copies = kCopies;
    r.lasTwin = std::move(twin);
    return r;
}

/// The repeated file's layout against the input's: counts, header fields kept, and each
/// chunk the same bytes and points as the input's chunk it copies, back to back.
void expectRepeatedLayout(const LazFile& input, const LazFile& output) {
    const io::LasHeader& in = input.header();
    const io::LasHeader& out = output.header();
    EXPECT_EQ(out.pointCount, kCopies * in.pointCount);
    EXPECT_EQ(out.pointFormat, in.pointFormat);
    EXPECT_EQ(out.recordLength, in.recordLength);
    EXPECT_EQ(out.bounds, in.bounds);
    EXPECT_EQ(out.scale, in.scale);
    EXPECT_EQ(out.evlrCount, in.evlrCount);
    EXPECT_TRUE(output.laszip().variableChunks());
    EXPECT_EQ(output.chunkListOrigin(), io::laz::ChunkListOrigin::Table);
    const std::size_t n = input.chunks().size();
    ASSERT_EQ(output.chunks().size(), kCopies * n);
    std::uint64_t expectedOffset = out.pointDataOffset + 8;
    std::vector<std::byte> inBytes;
    std::vector<std::byte> outBytes;
    for (std::size_t i = 0; i < output.chunks().size(); ++i) {
        const io::laz::LazChunk& copy = output.chunks()[i];
        const io::laz::LazChunk& original = input.chunks()[i % n];
        EXPECT_EQ(copy.offset, expectedOffset) << output.chunkLabel(i);
        EXPECT_EQ(copy.byteCount, original.byteCount) << output.chunkLabel(i);
        EXPECT_EQ(copy.pointCount, original.pointCount) << output.chunkLabel(i);
        input.readChunk(i % n, inBytes);
        output.readChunk(i, outBytes);
        EXPECT_EQ(outBytes, inBytes) << output.chunkLabel(i);
        expectedOffset += copy.byteCount;
    }
}

/// `once` repeated kCopies times.
template <typename T> std::vector<T> repeated(const std::vector<T>& once) {
    std::vector<T> all;
    for (std::uint32_t copy = 0; copy < kCopies; ++copy)
        all.insert(all.end(), once.begin(), once.end());
    return all;
}

/// The whole check of one pointwise file: layout, decoded records, and the twin.
void checkRepeatedWithTwin(const std::string& name) {
    const fs::path input = sharedLaz(name);
    test::TemporaryDirectory dir;
    const RepeatSummary summary =
        repeatLaz(request(input, dir / "repeated.laz", dir / "repeated.las"));
    const LazFile in = LazFile::open(input.string());
    const LazFile out = LazFile::open(dir.file("repeated.laz"));
    expectRepeatedLayout(in, out);
    EXPECT_EQ(summary.points, kCopies * in.header().pointCount);
    EXPECT_EQ(summary.chunks, kCopies * in.chunks().size());
    EXPECT_EQ(summary.lazBytes, fs::file_size(dir / "repeated.laz"));
    EXPECT_EQ(summary.lasBytes, fs::file_size(dir / "repeated.las"));

    const std::vector<std::byte> records = repeated(io::laz::test::decodeAll(in));
    const std::size_t length = in.header().recordLength;
    const int format = in.header().pointFormat;
    const auto decodedDifference =
        io::laz::test::firstDifference(io::laz::test::decodeAll(out), records, length, format);
    EXPECT_FALSE(decodedDifference) << name << ": " << *decodedDifference;
    const io::laz::test::LasRecords twin = io::laz::test::lasRecords(dir / "repeated.las");
    EXPECT_EQ(twin.pointFormat, format);
    const auto twinDifference = io::laz::test::firstDifference(twin.bytes, records, length, format);
    EXPECT_FALSE(twinDifference) << name << " twin: " << *twinDifference;

    const std::vector<Point3> points = repeated(io::readLasPoints(input.string()).points);
    EXPECT_EQ(io::readLasPoints(dir.file("repeated.laz")).points, points);
    const io::PointCloud lasCloud = io::readLasPoints(dir.file("repeated.las"));
    EXPECT_EQ(lasCloud.points, points);
    EXPECT_EQ(lasCloud.crsWkt, io::readLasPoints(input.string()).crsWkt);
    const io::LasHeader twinHeader = io::readLasHeader(dir.file("repeated.las"));
    EXPECT_FALSE(twinHeader.compressed);
    EXPECT_EQ(twinHeader.vlrCount + 1, in.header().vlrCount);
    EXPECT_EQ(twinHeader.bounds, in.header().bounds);
}

TEST(LazRepeat, LoneStarRepeatedThreeTimes) {
    SKIP_WITHOUT(sharedLaz("pdal__lone-star.laz"));
    checkRepeatedWithTwin("pdal__lone-star.laz");
}

TEST(LazRepeat, AutzenRepeatedThreeTimes) {
    SKIP_WITHOUT(sharedLaz("pdal__autzen_trim.laz"));
    checkRepeatedWithTwin("pdal__autzen_trim.laz");
}

TEST(LazRepeat, MegaplotRepeatedThreeTimes) {
    SKIP_WITHOUT(sharedLaz("lidr__Megaplot.laz"));
    checkRepeatedWithTwin("lidr__Megaplot.laz");
}

TEST(LazRepeat, LegacyCountsMultipliedAndReturnsKept) {
    // autzen_trim (LAS 1.2) has points of returns 1-4: each count is 3 x the input's.
    const fs::path input = sharedLaz("pdal__autzen_trim.laz");
    SKIP_WITHOUT(input);
    test::TemporaryDirectory dir;
    repeatLaz(request(input, dir / "repeated.laz"));
    const std::vector<std::byte> in = io::laz::test::fileBytes(input);
    const std::vector<std::byte> out = io::laz::test::fileBytes(dir / "repeated.laz");
    for (std::size_t at = 107; at < 131; at += 4)
        EXPECT_EQ(io::laz::loadLe<std::uint32_t>(out.data() + at),
                  kCopies * io::laz::loadLe<std::uint32_t>(in.data() + at))
            << "byte " << at;
}

/// A LAS 1.4 layered file: the container always; the points and the twin when the decoder
/// has compressor 3, else a --las run must fail and leave nothing behind.
void checkLayered(const std::string& name) {
    const fs::path input = sharedLaz(name);
    test::TemporaryDirectory dir;
    repeatLaz(request(input, dir / "repeated.laz"));
    const LazFile in = LazFile::open(input.string());
    const LazFile out = LazFile::open(dir.file("repeated.laz"));
    expectRepeatedLayout(in, out);
    const std::vector<std::byte> inBytes = io::laz::test::fileBytes(input);
    const std::vector<std::byte> outBytes = io::laz::test::fileBytes(dir / "repeated.laz");
    // LAS 1.4 wants the 64-bit counts; the legacy ones stay 0 as the input has them.
    EXPECT_EQ(io::laz::loadLe<std::uint64_t>(outBytes.data() + 247),
              kCopies * io::laz::loadLe<std::uint64_t>(inBytes.data() + 247));
    EXPECT_EQ(io::laz::loadLe<std::uint32_t>(outBytes.data() + 107), 0u);
    if (in.header().evlrCount > 0) {
        // The EVLRs follow the table, moved as a block with their offset.
        const std::uint64_t inSize = inBytes.size() - in.header().evlrStart;
        EXPECT_EQ(outBytes.size() - out.header().evlrStart, inSize);
        EXPECT_TRUE(std::equal(inBytes.begin() + static_cast<long>(in.header().evlrStart),
                               inBytes.end(),
                               outBytes.begin() + static_cast<long>(out.header().evlrStart)));
    }
    std::optional<io::PointCloud> original;
    try {
        original = io::readLasPoints(input.string());
    } catch (const InvalidInputError&) {
        // No layered decoder yet: --las needs one, and its failure writes nothing.
        test::TemporaryDirectory empty;
        EXPECT_THROW(repeatLaz(request(input, empty / "r.laz", empty / "r.las")),
                     InvalidInputError);
        EXPECT_TRUE(empty.entries().empty());
        return;
    }
    EXPECT_EQ(io::readLasPoints(dir.file("repeated.laz")).points, repeated(original->points));
    repeatLaz(request(input, dir / "twin.laz", dir / "twin.las"));
    EXPECT_EQ(io::readLasPoints(dir.file("twin.las")).points, repeated(original->points));
    // Every field of every record, not only what a TIN is built from.
    const io::laz::test::LasRecords twin = io::laz::test::lasRecords(dir / "twin.las");
    const auto difference =
        io::laz::test::firstDifference(twin.bytes, repeated(io::laz::test::decodeAll(in)),
                                       in.header().recordLength, in.header().pointFormat);
    EXPECT_FALSE(difference) << name << " twin: " << *difference;
    const io::LasHeader twinHeader = io::readLasHeader(dir.file("twin.las"));
    EXPECT_EQ(twinHeader.evlrCount, in.header().evlrCount);
    if (in.header().evlrCount > 0) {
        const std::vector<std::byte> twinBytes = io::laz::test::fileBytes(dir / "twin.las");
        EXPECT_EQ(twinBytes.size() - twinHeader.evlrStart, inBytes.size() - in.header().evlrStart);
        EXPECT_TRUE(std::equal(inBytes.begin() + static_cast<long>(in.header().evlrStart),
                               inBytes.end(),
                               twinBytes.begin() + static_cast<long>(twinHeader.evlrStart)));
    }
}

TEST(LazRepeat, LayeredFileWithSeveralExtraByteBlocks) {
    SKIP_WITHOUT(sharedLaz("pdal__las_with_several_extra_byte_bloc.laz"));
    checkLayered("pdal__las_with_several_extra_byte_bloc.laz");
}

TEST(LazRepeat, LayeredFileWithAnEvlr) {
    SKIP_WITHOUT(sharedLaz("laspy__1_4_w_evlr.laz"));
    checkLayered("laspy__1_4_w_evlr.laz");
}

TEST(LazRepeat, RefusesAnExistingOutputUnlessOverwrite) {
    const fs::path input = sharedLaz("lidr__Megaplot.laz");
    SKIP_WITHOUT(input);
    test::TemporaryDirectory dir;
    { std::ofstream(dir / "repeated.laz") << "keep me"; }
    EXPECT_THROW(repeatLaz(request(input, dir / "repeated.laz")), InvalidInputError);
    EXPECT_EQ(fs::file_size(dir / "repeated.laz"), 7u);
    RepeatRequest again = request(input, dir / "repeated.laz");
    again.overwrite = true;
    repeatLaz(again);
    EXPECT_EQ(LazFile::open(dir.file("repeated.laz")).chunks().size(), kCopies * 2);
    EXPECT_EQ(dir.entries(), std::set<std::string>{"repeated.laz"});
}

/// The one-line message of what `run` throws, or "" when it throws nothing.
template <typename Run> std::string errorOf(Run run) {
    try {
        run();
    } catch (const Error& error) {
        return error.what();
    }
    return "";
}

TEST(LazRepeat, RefusesWhatHasNoChunksToRepeat) {
    const fs::path unchunked = sharedLaz("pdal__simple-laszip-compressor-version-1.2r0.laz");
    const fs::path uncompressed = sharedLaz("lazrs__point10.las");
    const fs::path copc = sharedLaz("pdal__lone-star.copc.laz");
    SKIP_WITHOUT(unchunked);
    test::TemporaryDirectory dir;
    EXPECT_NE(errorOf([&] { repeatLaz(request(unchunked, dir / "a.laz")); }).find("compressor 1"),
              std::string::npos);
    EXPECT_NE(errorOf([&] { repeatLaz(request(uncompressed, dir / "a.laz")); }).find("not a LAZ"),
              std::string::npos);
    EXPECT_NE(errorOf([&] { repeatLaz(request(copc, dir / "a.laz")); }).find("COPC"),
              std::string::npos);
    EXPECT_NE(errorOf([&] { repeatLaz(request(unchunked, unchunked)); }).find("the input itself"),
              std::string::npos);
    EXPECT_TRUE(dir.entries().empty());
}

} // namespace
} // namespace terratin::lazrepeat

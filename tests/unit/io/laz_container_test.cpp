// Tests of the LAZ container: the LASzip VLR (every field, every malformed case with its own
// one-line error), the placing of chunks through the chunk table in real files (padding,
// the LASzip VLR not last, EVLRs after the table, 0 points, variable COPC chunks, the
// unchunked compressor), and files edited in memory to hold what no shared file does: a
// streaming writer's -1 pointer, a missing table, lying counts, truncation.

#include "laz_test_files.hpp"

#include "chunk_decoder.hpp"
#include "chunk_table.hpp"
#include "laszip_vlr.hpp"
#include "laz_bytes.hpp"
#include "laz_file.hpp"
#include "terratin/error.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <functional>
#include <random>
#include <string>
#include <vector>

namespace terratin::io::laz {
namespace {

using test::fileBytes;
using test::sharedLaz;

/// A LASzip VLR payload: compressor, coder, chunk size and (type, size, version) items.
std::vector<std::byte> laszipPayload(std::uint16_t compressor, std::uint16_t coder,
                                     std::uint32_t chunkSize,
                                     const std::vector<std::array<std::uint16_t, 3>>& items) {
    std::vector<std::byte> bytes(34 + 6 * items.size());
    storeLe(bytes.data(), compressor);
    storeLe(bytes.data() + 2, coder);
    bytes[4] = std::byte{2};
    bytes[5] = std::byte{2};
    storeLe(bytes.data() + 12, chunkSize);
    storeLe(bytes.data() + 16, std::int64_t{-1});
    storeLe(bytes.data() + 24, std::int64_t{-1});
    storeLe(bytes.data() + 32, static_cast<std::uint16_t>(items.size()));
    for (std::size_t i = 0; i < items.size(); ++i)
        for (std::size_t f = 0; f < 3; ++f)
            storeLe(bytes.data() + 34 + 6 * i + 2 * f, items[i][f]);
    return bytes;
}

/// The message of the InvalidInputError that `run` throws; fails the test if none.
template <typename Run> std::string errorOf(Run run) {
    try {
        run();
    } catch (const InvalidInputError& error) {
        return error.what();
    }
    ADD_FAILURE() << "no InvalidInputError";
    return {};
}

TEST(LazLaszipRecord, ReadsEveryField) {
    const LaszipRecord record =
        parseLaszipRecord(laszipPayload(2, 0, 50000, {{6, 20, 2}, {7, 8, 2}, {0, 5, 2}}), "a.laz");
    EXPECT_EQ(record.compressor, Compressor::PointwiseChunked);
    EXPECT_EQ(record.coder, 0);
    EXPECT_EQ(record.versionMajor, 2);
    EXPECT_EQ(record.chunkSize, 50000u);
    EXPECT_EQ(record.specialEvlrCount, -1);
    ASSERT_EQ(record.items.size(), 3u);
    EXPECT_EQ(record.items[1].type, ItemType::GpsTime11);
    EXPECT_EQ(record.items[2].size, 5);
    EXPECT_EQ(record.recordLength(), 33u);
    EXPECT_TRUE(record.chunked());
    EXPECT_FALSE(record.variableChunks());
    EXPECT_TRUE(
        parseLaszipRecord(laszipPayload(3, 0, 0xFFFFFFFFu, {{10, 30, 3}}), "a").variableChunks());
    EXPECT_TRUE(parseLaszipRecord(laszipPayload(3, 0, 0, {{10, 30, 3}}), "a").variableChunks());
}

TEST(LazLaszipRecord, EachMalformedFieldHasItsOwnError) {
    struct Case {
        std::vector<std::byte> payload;
        const char* message;
    };
    std::vector<std::byte> short_payload = laszipPayload(2, 0, 50000, {{6, 20, 2}});
    short_payload.resize(30);
    std::vector<std::byte> missing_item = laszipPayload(2, 0, 50000, {{6, 20, 2}, {7, 8, 2}});
    missing_item.resize(missing_item.size() - 6);
    const std::vector<Case> cases{
        {short_payload, "fewer than the 34"},
        {missing_item, "lists 2 items, which need 46 bytes, but it has 40"},
        {laszipPayload(2, 15, 50000, {{6, 20, 2}}),
         "coder 15 is not the arithmetic coder (0), the only one LASzip defines"},
        {laszipPayload(16, 0, 50000, {{6, 20, 2}}), "compressor 16 is unknown"},
        {laszipPayload(2, 0, 50000, {{6, 20, 2}, {22, 8, 2}}),
         "item 2 of the LASzip record: item type 22 is unknown"},
        {laszipPayload(2, 0, 50000, {{6, 21, 2}}),
         "POINT10 has size 21, but the format fixes it at 20"},
        {laszipPayload(2, 0, 50000, {{6, 20, 6}}),
         "POINT10 version 6 is unknown (LASzip defines 0-2)"},
        {laszipPayload(3, 0, 50000, {{10, 30, 1}}), "POINT14 version 1 is unknown"},
        {laszipPayload(2, 0, 50000, {{6, 20, 2}, {0, 0, 2}}), "BYTE has size 0"},
        {laszipPayload(2, 0, 50000, {}), "lists no items"},
    };
    for (const Case& c : cases) {
        const std::string message = errorOf([&] { (void)parseLaszipRecord(c.payload, "x.laz"); });
        EXPECT_NE(message.find(c.message), std::string::npos) << message;
        EXPECT_NE(message.find("'x.laz'"), std::string::npos) << message;
    }
}

TEST(LazFileLayout, BrokenLaszipRecordsEachSayWhatIsWrong) {
    struct Case {
        const char* file;
        const char* message;
    };
    for (const Case& c : {Case{"laszip__broken_coder.laz", "coder 15 is not the arithmetic coder"},
                          Case{"laszip__broken_compressor.laz", "compressor 16 is unknown"},
                          Case{"laszip__broken_type.laz", "item type 22 is unknown"},
                          Case{"laszip__broken_version.laz", "POINT10 version 6 is unknown"}}) {
        const auto path = sharedLaz(c.file);
        if (!std::filesystem::exists(path))
            GTEST_SKIP() << "shared LAZ test files absent";
        const std::string message = errorOf([&] { (void)LazFile::open(path.string()); });
        EXPECT_NE(message.find(c.message), std::string::npos) << message;
        EXPECT_NE(message.find(c.file), std::string::npos) << message;
        EXPECT_EQ(message.find('\n'), std::string::npos);
    }
}

TEST(LazFileLayout, PlacesTheChunksOfRealFiles) {
    const auto path = sharedLaz("pdal__autzen_trim.laz");
    if (!std::filesystem::exists(path))
        GTEST_SKIP() << "shared LAZ test files absent";
    const LazFile file = LazFile::open(path.string());
    EXPECT_EQ(file.header().pointCount, 110000u);
    EXPECT_EQ(file.header().pointFormat, 3);
    EXPECT_EQ(file.chunkListOrigin(), ChunkListOrigin::Table);
    ASSERT_EQ(file.chunks().size(), 3u);
    std::array<std::byte, 8> pointer{};
    file.readBytes(file.header().pointDataOffset, pointer);
    std::uint64_t offset = file.header().pointDataOffset + 8;
    const std::array<std::uint64_t, 3> counts{50000, 50000, 10000};
    for (std::size_t i = 0; i < 3; ++i) {
        EXPECT_EQ(file.chunks()[i].offset, offset);
        EXPECT_EQ(file.chunks()[i].pointCount, counts[i]);
        EXPECT_EQ(file.chunks()[i].firstPoint, 50000 * i);
        offset += file.chunks()[i].byteCount;
    }
    // The chunks end where the table starts.
    EXPECT_EQ(offset, loadLe<std::uint64_t>(pointer.data()));
}

TEST(LazFileLayout, HandlesPaddingEvlrsEmptyFilesVariableAndUnchunkedLayouts) {
    struct Case {
        const char* file;
        std::size_t chunks;
        std::uint64_t points;
        ChunkListOrigin origin;
    };
    for (const Case& c : {Case{"lazperf__no-points-1.3.laz", 0, 0, ChunkListOrigin::Table},
                          Case{"rlas__example.laz", 1, 30, ChunkListOrigin::Table},
                          Case{"laspy__1_4_w_evlr.laz", 1, 1000, ChunkListOrigin::Table},
                          Case{"laspy__simple.copc.laz", 65, 1065, ChunkListOrigin::Table},
                          Case{"rlas__example.copc.laz", 1, 30, ChunkListOrigin::Table},
                          Case{"pdal__simple-laszip-compressor-version-1.2r0.laz", 1, 1065,
                               ChunkListOrigin::NotChunked},
                          Case{"lastools__fusa.laz", 6, 277573, ChunkListOrigin::Table}}) {
        const auto path = sharedLaz(c.file);
        if (!std::filesystem::exists(path))
            GTEST_SKIP() << "shared LAZ test files absent";
        const LazFile file = LazFile::open(path.string());
        EXPECT_EQ(file.chunks().size(), c.chunks) << c.file;
        EXPECT_EQ(file.header().pointCount, c.points) << c.file;
        EXPECT_EQ(file.chunkListOrigin(), c.origin) << c.file;
        std::uint64_t points = 0;
        for (const LazChunk& chunk : file.chunks()) {
            EXPECT_EQ(chunk.firstPoint, points) << c.file;
            EXPECT_LE(chunk.offset + chunk.byteCount, file.fileSize()) << c.file;
            points += chunk.pointCount;
        }
        EXPECT_EQ(points, c.points) << c.file;
    }
}

/// A shared file's bytes, for editing in memory.
class EditedLaz : public ::testing::Test {
protected:
    bool load(const char* name) {
        const auto path = sharedLaz(name);
        if (!std::filesystem::exists(path))
            return false;
        bytes = fileBytes(path);
        pointData = loadLe<std::uint32_t>(bytes.data() + 96);
        tableStart = loadLe<std::uint64_t>(bytes.data() + pointData);
        original = LazFile::open(path.string()).chunks();
        return true;
    }
    void setPointer(std::int64_t value) { storeLe(bytes.data() + pointData, value); }
    [[nodiscard]] LazFile open() const { return LazFile::fromMemory(bytes, "edited.laz"); }
    void expectOriginalChunks(const LazFile& file) const {
        ASSERT_EQ(file.chunks().size(), original.size());
        for (std::size_t i = 0; i < original.size(); ++i) {
            EXPECT_EQ(file.chunks()[i].offset, original[i].offset);
            EXPECT_EQ(file.chunks()[i].byteCount, original[i].byteCount);
            EXPECT_EQ(file.chunks()[i].pointCount, original[i].pointCount);
        }
    }

    std::vector<std::byte> bytes;
    std::uint32_t pointData = 0;
    std::uint64_t tableStart = 0;
    std::vector<LazChunk> original;
};

TEST_F(EditedLaz, StreamingWritersTrailingPointerIsFollowed) {
    if (!load("lidr__Megaplot.laz"))
        GTEST_SKIP() << "shared LAZ test files absent";
    setPointer(-1);
    bytes.resize(bytes.size() + 8);
    storeLe(bytes.data() + bytes.size() - 8, tableStart);
    const LazFile file = open();
    EXPECT_EQ(file.chunkListOrigin(), ChunkListOrigin::TrailingPointer);
    expectOriginalChunks(file);
}

TEST_F(EditedLaz, MissingTableIsRebuiltByDecoding) {
    if (!load("lidr__Megaplot.laz"))
        GTEST_SKIP() << "shared LAZ test files absent";
    bytes.resize(tableStart); // the table never written
    for (const std::int64_t pointer : {std::int64_t{-1}, std::int64_t{pointData}}) {
        setPointer(pointer);
        const LazFile file = open();
        EXPECT_EQ(file.chunkListOrigin(), ChunkListOrigin::Rebuilt);
        expectOriginalChunks(file);
    }
}

TEST_F(EditedLaz, MissingTableOfLayeredChunksIsRebuiltFromTheirLayouts) {
    // Fixed chunks (14), then a COPC file's variable ones (65) with EVLRs after the table.
    for (const char* name :
         {"pdal__las_with_several_extra_byte_bloc.laz", "laspy__simple.copc.laz"}) {
        if (!load(name))
            GTEST_SKIP() << "shared LAZ test files absent";
        setPointer(pointData);
        const LazFile file = open();
        EXPECT_EQ(file.chunkListOrigin(), ChunkListOrigin::Rebuilt) << name;
        expectOriginalChunks(file);
    }
}

TEST_F(EditedLaz, MissingTableOfVariablePointwiseChunksIsAClearError) {
    if (!load("lidr__Megaplot.laz"))
        GTEST_SKIP() << "shared LAZ test files absent";
    // The LASzip VLR's chunk size (payload byte 12) set to variable.
    const std::string_view user = "laszip encoded";
    const auto at = std::search(bytes.begin(), bytes.end(), user.begin(), user.end(),
                                [](std::byte b, char c) { return static_cast<char>(b) == c; });
    ASSERT_NE(at, bytes.end());
    const auto payload = static_cast<std::size_t>(at - bytes.begin()) - 2 + 54;
    storeLe(bytes.data() + payload + 12, std::uint32_t{0xFFFFFFFFu});
    setPointer(pointData);
    EXPECT_NE(errorOf([&] { (void)open(); }).find("variable point counts, which only the table"),
              std::string::npos);
}

TEST_F(EditedLaz, LyingTablesAndHeadersAreClearErrors) {
    if (!load("pdal__autzen_trim.laz"))
        GTEST_SKIP() << "shared LAZ test files absent";
    const std::vector<std::byte> good = bytes;
    struct Edit {
        std::function<void()> apply;
        const char* message;
    };
    const std::vector<Edit> edits{
        {[&] { setPointer(static_cast<std::int64_t>(bytes.size()) + 100); }, "lies outside"},
        {[&] { setPointer(5); }, "lies outside"},
        {[&] { storeLe(bytes.data() + tableStart, std::uint32_t{5}); },
         "chunk table version 5 is unknown"},
        {[&] { storeLe(bytes.data() + tableStart + 4, std::uint32_t{2}); },
         "lists 2 chunks, but 110000 points in chunks of 50000 make 3"},
        {[&] { storeLe(bytes.data() + 107, std::uint32_t{160000}); }, "make 4"},
        {[&] { bytes.resize(tableStart + 9); }, "chunk table is truncated or corrupt"},
        {[&] { bytes.resize(bytes.size() / 2); }, "(truncated?)"},
        {[&] { storeLe(bytes.data() + 105, std::uint16_t{36}); },
         "the LASzip items add up to 34 bytes per point, but the header's point record length is "
         "36"},
        {[&] { bytes[0] = std::byte{'X'}; }, "no LASF signature"},
        {[&] { storeLe(bytes.data() + 24, std::uint8_t{2}); }, "LAS version 2.2 is not supported"},
        {[&] { storeLe(bytes.data() + 96, std::uint32_t{100}); },
         "lies inside the 227-byte header"},
        {[&] {
             storeLe(bytes.data() + loadLe<std::uint16_t>(bytes.data() + 94) + 20,
                     std::uint16_t{0xFFFF});
         },
         "variable length record 1 of"},
        {[&] { bytes.resize(200); }, "shorter than a LAS header"},
    };
    for (std::size_t i = 0; i < edits.size(); ++i) {
        bytes = good;
        edits[i].apply();
        const std::string message = errorOf([&] { (void)open(); });
        EXPECT_NE(message.find(edits[i].message), std::string::npos)
            << "edit " << i << ": " << message;
        EXPECT_NE(message.find("'edited.laz'"), std::string::npos) << message;
    }
}

TEST_F(EditedLaz, NoLaszipRecordIsNotALazFile) {
    if (!load("lazrs__point10.laz"))
        GTEST_SKIP() << "shared LAZ test files absent";
    // Rename the user id of every VLR that could be the LASzip one.
    const std::uint16_t headerSize = loadLe<std::uint16_t>(bytes.data() + 94);
    std::size_t at = headerSize;
    for (std::uint32_t i = 0; i < loadLe<std::uint32_t>(bytes.data() + 100); ++i) {
        bytes[at + 2] = std::byte{'X'};
        at += 54 + loadLe<std::uint16_t>(bytes.data() + at + 20);
    }
    EXPECT_NE(errorOf([&] { (void)open(); }).find("no LASzip record"), std::string::npos);
}

TEST_F(EditedLaz, DamagedHeadersAndTablesFailCleanly) {
    // Random bytes of the header, the VLRs, the table pointer and the table changed: opening
    // and decoding (in bounded pieces, as a reader would) either works or throws
    // InvalidInputError; nothing is read outside the file (checked by the sanitizers).
    if (!load("lazrs__point-time-color.laz"))
        GTEST_SKIP() << "shared LAZ test files absent";
    const std::vector<std::byte> good = bytes;
    std::mt19937 random(5);
    const auto anyOf = [&](std::size_t from, std::size_t to) {
        return from + random() % (to - from);
    };
    int failed = 0;
    for (int trial = 0; trial < 400; ++trial) {
        bytes = good;
        for (int edit = 0; edit < 1 + trial % 4; ++edit) {
            const std::size_t at =
                trial % 2 == 0 ? anyOf(0, pointData + 8) : anyOf(tableStart, bytes.size());
            bytes[at] = static_cast<std::byte>(random());
        }
        try {
            const LazFile file = open();
            ChunkDecoder decoder(file.laszip(), file.name());
            std::vector<std::byte> chunk;
            std::vector<std::byte> piece(4096 * decoder.recordLength());
            for (std::size_t i = 0; i < file.chunks().size(); ++i) {
                file.readChunk(i, chunk);
                decoder.begin(chunk, file.chunks()[i].pointCount, file.chunkLabel(i));
                while (decoder.pointsLeft() > 0) {
                    const std::uint64_t count = std::min<std::uint64_t>(decoder.pointsLeft(), 4096);
                    decoder.decodeNext(std::span(piece).first(count * decoder.recordLength()));
                }
            }
        } catch (const InvalidInputError&) {
            ++failed;
        }
    }
    EXPECT_GT(failed, 100);
}

TEST(LazChunkTable, DecodesNothingFromNoEntriesAndFailsOnTooFewBytes) {
    EXPECT_TRUE(decodeChunkTableEntries({}, 0, false, "t.laz").empty());
    const std::vector<std::byte> few(3, std::byte{0x55});
    EXPECT_NE(errorOf([&] {
                  (void)decodeChunkTableEntries(few, 40, true, "t.laz");
              }).find("chunk table is truncated or corrupt"),
              std::string::npos);
}

} // namespace
} // namespace terratin::io::laz

// Tests of how the layered LAZ compressor (3) fails: truncated chunks, layer sizes that run
// past the chunk, a point count that disagrees with the chunk table, a layer that ends too
// soon, random damage, and item kinds or versions it does not decode. Each is one line naming
// the file and the chunk, never a crash or a read outside the chunk (the dev build runs these
// under AddressSanitizer and UndefinedBehaviorSanitizer).

#include "laz_test_files.hpp"

#include "chunk_decoder.hpp"
#include "laszip_vlr.hpp"
#include "laz_file.hpp"
#include "terratin/error.hpp"

#include <gtest/gtest.h>

#include <optional>
#include <random>
#include <string>
#include <vector>

namespace terratin::io::laz {
namespace {

using test::sharedLaz;

/// laspy__1_4_w_evlr.laz: one chunk of 1,000 POINT14 points, nine layers.
constexpr const char* kSmallFile = "laspy__1_4_w_evlr.laz";
constexpr std::size_t kPoint14Layers = 9;
/// Where the layer sizes of a POINT14-only chunk start: after the raw record and the count.
constexpr std::size_t kLayerSizesAt = 30 + 4;

std::optional<LazFile> openShared(const std::string& name) {
    const auto path = sharedLaz(name);
    if (!std::filesystem::exists(path))
        return std::nullopt;
    return LazFile::open(path.string());
}

/// The message of the InvalidInputError that decoding `bytes` as `points` points throws, or
/// nothing when it decodes.
std::optional<std::string> decodeError(const LazFile& file, std::span<const std::byte> bytes,
                                       std::uint64_t points,
                                       FieldSelection fields = FieldSelection::Every) {
    ChunkDecoder decoder(file.laszip(), file.name(), fields);
    std::vector<std::byte> records(points * file.header().recordLength);
    try {
        decoder.decode(bytes, points, records, file.chunkLabel(0));
    } catch (const InvalidInputError& error) {
        return std::string(error.what());
    }
    return std::nullopt;
}

void expectOneLine(const std::optional<std::string>& message, const std::string& part) {
    ASSERT_TRUE(message) << "no error; expected one about " << part;
    EXPECT_NE(message->find(part), std::string::npos) << *message;
    EXPECT_NE(message->find(kSmallFile), std::string::npos) << *message;
    EXPECT_EQ(message->find('\n'), std::string::npos) << *message;
}

TEST(LazLayeredErrors, TruncatedChunksAreOneLineErrors) {
    const std::optional<LazFile> file = openShared(kSmallFile);
    if (!file)
        GTEST_SKIP() << "shared LAZ test files absent";
    std::vector<std::byte> bytes;
    file->readChunk(0, bytes);
    const std::uint64_t points = file->chunks()[0].pointCount;
    for (const std::size_t kept :
         {std::size_t{0}, std::size_t{29}, std::size_t{30}, std::size_t{50}, std::size_t{69},
          std::size_t{70}, std::size_t{3000}, bytes.size() - 1}) {
        SCOPED_TRACE("kept " + std::to_string(kept) + " bytes");
        expectOneLine(decodeError(*file, std::span(bytes).first(kept), points),
                      "chunk 1 of 1 is truncated or corrupt");
    }
}

TEST(LazLayeredErrors, LayerSizesPastTheChunkAreErrors) {
    const std::optional<LazFile> file = openShared(kSmallFile);
    if (!file)
        GTEST_SKIP() << "shared LAZ test files absent";
    std::vector<std::byte> good;
    file->readChunk(0, good);
    for (std::size_t layer = 0; layer < kPoint14Layers; ++layer) {
        for (const std::uint32_t size : {0xFFFFFFFFu, 0x7FFFFFF0u, 10000u}) {
            std::vector<std::byte> bytes = good;
            storeLe(bytes.data() + kLayerSizesAt + 4 * layer, size);
            expectOneLine(decodeError(*file, bytes, file->chunks()[0].pointCount),
                          "layer sizes add up to more than");
        }
    }
}

TEST(LazLayeredErrors, APointCountOtherThanTheTablesIsAnError) {
    const std::optional<LazFile> file = openShared(kSmallFile);
    if (!file)
        GTEST_SKIP() << "shared LAZ test files absent";
    std::vector<std::byte> bytes;
    file->readChunk(0, bytes);
    expectOneLine(decodeError(*file, bytes, 1001),
                  "it says it holds 1000 points, the chunk table 1001");
    storeLe(bytes.data() + 30, std::uint32_t{999});
    expectOneLine(decodeError(*file, bytes, 1000),
                  "it says it holds 999 points, the chunk table 1000");
}

TEST(LazLayeredErrors, ALayerThatEndsTooSoonIsNamedAndTinFieldsNeverReadIt) {
    // The last layer (GPS time) cut to 8 bytes: decoding every field runs out of it; the TIN
    // fields never touch it and decode exactly as before, which shows the layer is skipped.
    const std::optional<LazFile> file = openShared(kSmallFile);
    if (!file)
        GTEST_SKIP() << "shared LAZ test files absent";
    std::vector<std::byte> good;
    file->readChunk(0, good);
    const std::size_t sizeAt = kLayerSizesAt + 4 * (kPoint14Layers - 1);
    const auto timeBytes = loadLe<std::uint32_t>(good.data() + sizeAt);
    std::vector<std::byte> bytes(good.begin(), good.end() - (timeBytes - 8));
    storeLe(bytes.data() + sizeAt, std::uint32_t{8});
    const std::uint64_t points = file->chunks()[0].pointCount;
    expectOneLine(decodeError(*file, bytes, points),
                  "chunk 1 of 1 is truncated or corrupt: its gps time layer (8 bytes) ends "
                  "before its 1000 points do");

    ChunkDecoder decoder(file->laszip(), file->name(), FieldSelection::TinFields);
    std::vector<std::byte> cut(points * 30), whole(points * 30);
    decoder.decode(bytes, points, cut, "cut");
    decoder.decode(good, points, whole, "whole");
    EXPECT_TRUE(cut == whole);
}

TEST(LazLayeredErrors, DamagedChunksNeverReadOutsideTheirBytes) {
    // Random bytes changed: the decoder either notices (InvalidInputError) or yields other
    // points, but stays inside the chunk.
    for (const char* name : {"laspy__fullwave.laz", "untwine__eb.laz", "laspy__append-bug.laz"}) {
        const std::optional<LazFile> file = openShared(name);
        if (!file)
            GTEST_SKIP() << "shared LAZ test files absent";
        std::vector<std::byte> good;
        file->readChunk(0, good);
        const std::uint64_t points = file->chunks()[0].pointCount;
        std::mt19937 random(7);
        int noticed = 0;
        for (int trial = 0; trial < 40; ++trial) {
            std::vector<std::byte> bytes = good;
            for (int flips = 0; flips < 1 + trial % 8; ++flips)
                bytes[random() % bytes.size()] = static_cast<std::byte>(random());
            const FieldSelection fields =
                trial % 2 == 0 ? FieldSelection::Every : FieldSelection::TinFields;
            if (decodeError(*file, bytes, points, fields))
                ++noticed;
        }
        EXPECT_GT(noticed, 0) << name;
    }
}

/// A LASzip record of the layered compressor (or `compressor`) with `items`.
LaszipRecord record(std::vector<Item> items, Compressor compressor = Compressor::LayeredChunked) {
    LaszipRecord r;
    r.compressor = compressor;
    r.chunkSize = 50000;
    r.items = std::move(items);
    return r;
}

std::string constructionError(const LaszipRecord& r) {
    try {
        ChunkDecoder decoder(r, "made.laz");
    } catch (const InvalidInputError& error) {
        return error.what();
    }
    return "no error";
}

TEST(LazLayeredErrors, ItemsAndVersionsItCannotDecodeAreNamed) {
    const Item point14{ItemType::Point14, 30, 3};
    struct Case {
        LaszipRecord record;
        const char* message;
    };
    const std::vector<Case> cases{
        {record({{ItemType::Point14, 30, 4}}),
         "POINT14 version 4 is not supported by this LAZ decoder (it decodes version 3; "
         "version 4 comes with LAS 1.5)"},
        {record({point14, {ItemType::RgbNir14, 8, 4}}), "RGBNIR14 version 4 is not supported"},
        {record({point14, {ItemType::Byte14, 3, 0}}), "BYTE14 version 0 means stored "
                                                      "uncompressed"},
        {record({{ItemType::Point10, 20, 2}}), "item 1 is POINT10, but the layered compressor "
                                               "(3) stores POINT14 first"},
        {record({point14, {ItemType::GpsTime11, 8, 2}}), "item 2 is GPSTIME11"},
        {record({point14, point14}), "item 2 is POINT14"},
        {record({point14}, Compressor::PointwiseChunked),
         "POINT14 is stored only by the layered compressor (3), not by the pointwise one (2)"},
    };
    for (const Case& c : cases) {
        const std::string message = constructionError(c.record);
        EXPECT_NE(message.find(c.message), std::string::npos) << message;
        EXPECT_NE(message.find("made.laz"), std::string::npos) << message;
    }
}

} // namespace
} // namespace terratin::io::laz

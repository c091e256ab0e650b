/// @file
/// The chunk loop of the pointwise LAZ compressors (1 and 2): the raw first point seeds every
/// item decoder, then each further point is decoded item after item from one arithmetic
/// stream (see chunk_decoder.hpp). The layered compressor (3) has a loop of its own
/// (layered_chunk.hpp); this file hands its chunks over.

#include "chunk_decoder.hpp"

#include "extra_bytes_decoder.hpp"
#include "gpstime_decoder.hpp"
#include "layered_chunk.hpp"
#include "laz_error.hpp"
#include "point10_decoder.hpp"
#include "range_decoder.hpp"
#include "rgb_decoder.hpp"
#include "wavepacket_decoder.hpp"

#include <cstring>
#include <stdexcept>
#include <variant>
#include <vector>

namespace terratin::io::laz {

namespace {

using ItemDecoder = std::variant<Point10V1Decoder, Point10V2Decoder, GpsTime11V1Decoder,
                                 GpsTime11V2Decoder, Rgb12V1Decoder, Rgb12V2Decoder,
                                 ExtraBytesV1Decoder, ExtraBytesV2Decoder, WavePacket13V1Decoder>;

/// An item decoder and where its bytes sit in the record.
struct PlacedItem {
    ItemDecoder decoder;
    std::size_t offset = 0;
};

template <typename V1, typename V2, typename... Args>
ItemDecoder versioned(std::uint16_t version, Args... args) {
    if (version == 1)
        return ItemDecoder(std::in_place_type<V1>, args...);
    return ItemDecoder(std::in_place_type<V2>, args...);
}

[[noreturn]] void unsupportedItem(const Item& item, Compressor compressor,
                                  std::string_view fileName) {
    const std::string name = itemName(static_cast<std::uint16_t>(item.type)) + " version " +
                             std::to_string(item.version);
    if (item.version == 0)
        throwInvalidLaz(fileName, name + " means stored uncompressed, which LASzip does not "
                                         "decode inside a compressed point stream");
    if (item.type >= ItemType::Point14)
        throwInvalidLaz(fileName, itemName(static_cast<std::uint16_t>(item.type)) +
                                      " is stored only by the layered compressor (3), not by "
                                      "the pointwise one (" +
                                      std::to_string(static_cast<int>(compressor)) + ")");
    throwInvalidLaz(fileName, name + " is not supported by this LAZ decoder yet (it decodes "
                                     "POINT10, GPSTIME11, RGB12 and BYTE versions 1 and 2, "
                                     "WAVEPACKET13 version 1)");
}

ItemDecoder makeItemDecoder(const Item& item, Compressor compressor, std::string_view fileName) {
    if (item.version != 1 && item.version != 2)
        unsupportedItem(item, compressor, fileName);
    switch (item.type) {
    case ItemType::WavePacket13:
        if (item.version != 1)
            unsupportedItem(item, compressor, fileName);
        return ItemDecoder(std::in_place_type<WavePacket13V1Decoder>);
    case ItemType::Point10:
        return versioned<Point10V1Decoder, Point10V2Decoder>(item.version);
    case ItemType::GpsTime11:
        return versioned<GpsTime11V1Decoder, GpsTime11V2Decoder>(item.version);
    case ItemType::Rgb12:
        return versioned<Rgb12V1Decoder, Rgb12V2Decoder>(item.version);
    case ItemType::Byte:
        return versioned<ExtraBytesV1Decoder, ExtraBytesV2Decoder>(item.version,
                                                                   std::size_t{item.size});
    default:
        unsupportedItem(item, compressor, fileName);
    }
}

} // namespace

struct ChunkDecoder::State {
    std::string fileName;
    Compressor compressor = Compressor::None;
    std::size_t recordLength = 0;
    std::vector<PlacedItem> items;
    /// The layered compressor's own loop; null for the others.
    std::unique_ptr<LayeredChunkDecoder> layered;
    RangeDecoder decoder;
    std::span<const std::byte> chunk;
    std::uint64_t pointCount = 0;
    std::uint64_t pointsDone = 0;
    std::string label;

    void decodeCompressed(std::span<std::byte> records);
    void decodeLayered(std::span<std::byte> records);
    void startFromRawPoint(std::byte* record);
    void checkStream() const;
    [[noreturn]] void truncated() const;
};

ChunkDecoder::ChunkDecoder(const LaszipRecord& record, std::string_view fileName,
                           FieldSelection fields)
    : m_state(std::make_unique<State>()) {
    State& s = *m_state;
    s.fileName = std::string(fileName);
    s.compressor = record.compressor;
    s.recordLength = record.recordLength();
    if (record.compressor == Compressor::LayeredChunked) {
        s.layered = std::make_unique<LayeredChunkDecoder>(record, fileName, fields);
        return;
    }
    // The pointwise compressors store every field in one stream: all are decoded, whatever
    // `fields` asks for.
    if (record.compressor == Compressor::None)
        return;
    std::size_t offset = 0;
    for (const Item& item : record.items) {
        s.items.push_back({makeItemDecoder(item, record.compressor, fileName), offset});
        offset += item.size;
    }
}

ChunkDecoder::~ChunkDecoder() = default;
ChunkDecoder::ChunkDecoder(ChunkDecoder&&) noexcept = default;
ChunkDecoder& ChunkDecoder::operator=(ChunkDecoder&&) noexcept = default;

std::size_t ChunkDecoder::recordLength() const {
    return m_state->recordLength;
}

void ChunkDecoder::begin(std::span<const std::byte> chunk, std::uint64_t pointCount,
                         std::string label) {
    State& s = *m_state;
    s.chunk = chunk;
    s.pointCount = pointCount;
    s.pointsDone = 0;
    s.label = std::move(label);
}

std::uint64_t ChunkDecoder::pointsLeft() const {
    return m_state->pointCount - m_state->pointsDone;
}

std::size_t ChunkDecoder::bytesUsed() const {
    const State& s = *m_state;
    if (s.compressor == Compressor::None)
        return static_cast<std::size_t>(s.pointsDone) * s.recordLength;
    if (s.pointsDone == 0)
        return 0;
    return s.layered ? s.layered->chunkBytes() : s.recordLength + s.decoder.consumed();
}

void ChunkDecoder::decodeNext(std::span<std::byte> records) {
    State& s = *m_state;
    if (records.size() % s.recordLength != 0)
        throw std::invalid_argument("ChunkDecoder: a buffer of " + std::to_string(records.size()) +
                                    " bytes is no whole number of " +
                                    std::to_string(s.recordLength) + "-byte records");
    const std::uint64_t count = records.size() / s.recordLength;
    if (count > s.pointCount - s.pointsDone)
        throw std::invalid_argument("ChunkDecoder: " + std::to_string(count) +
                                    " points asked for, " +
                                    std::to_string(s.pointCount - s.pointsDone) + " left");
    if (count == 0)
        return;
    if (s.compressor == Compressor::None) {
        // Uncompressed records, as in a LAS file.
        const std::uint64_t from = s.pointsDone * s.recordLength;
        if (from + records.size() > s.chunk.size())
            s.truncated();
        std::memcpy(records.data(), s.chunk.data() + from, records.size());
        s.pointsDone += count;
        return;
    }
    if (s.layered)
        s.decodeLayered(records);
    else
        s.decodeCompressed(records);
}

std::size_t ChunkDecoder::decode(std::span<const std::byte> chunk, std::uint64_t pointCount,
                                 std::span<std::byte> records, std::string label) {
    begin(chunk, pointCount, std::move(label));
    decodeNext(records);
    return bytesUsed();
}

void ChunkDecoder::State::decodeCompressed(std::span<std::byte> records) {
    std::byte* record = records.data();
    std::byte* const end = records.data() + records.size();
    if (pointsDone == 0) {
        startFromRawPoint(record);
        record += recordLength;
    }
    for (; record != end; record += recordLength) {
        for (PlacedItem& item : items) {
            std::byte* const field = record + item.offset;
            std::visit([&](auto& itemDecoder) { itemDecoder.decode(decoder, field); },
                       item.decoder);
        }
    }
    pointsDone += records.size() / recordLength;
    checkStream();
}

void ChunkDecoder::State::decodeLayered(std::span<std::byte> records) {
    std::span<std::byte> rest = records;
    if (pointsDone == 0) {
        layered->start(chunk, pointCount, label, records.data());
        rest = records.subspan(recordLength);
    }
    layered->decode(rest);
    pointsDone += records.size() / recordLength;
}

void ChunkDecoder::State::startFromRawPoint(std::byte* record) {
    // LASzip's pointwise layout: the chunk's first record verbatim, then the coded stream.
    if (chunk.size() < recordLength)
        truncated();
    std::memcpy(record, chunk.data(), recordLength);
    for (PlacedItem& item : items) {
        const std::byte* const field = record + item.offset;
        std::visit([&](auto& itemDecoder) { itemDecoder.start(field); }, item.decoder);
    }
    decoder.start(chunk.data() + recordLength, chunk.data() + chunk.size());
}

void ChunkDecoder::State::checkStream() const {
    if (decoder.overran())
        truncated();
    if (decoder.corrupt())
        throwInvalidLaz(fileName, label + " is corrupt: its arithmetic-coded stream holds a value "
                                          "no LASzip writer produces");
}

void ChunkDecoder::State::truncated() const {
    throwInvalidLaz(fileName, label + " is truncated or corrupt: its " +
                                  std::to_string(pointCount) + " points need more than its " +
                                  std::to_string(chunk.size()) + " bytes");
}

} // namespace terratin::io::laz

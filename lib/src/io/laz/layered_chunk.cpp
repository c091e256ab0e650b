/// @file
/// The chunk loop of the layered LAZ compressor (see layered_chunk.hpp).

#include "layered_chunk.hpp"

#include "laz_bytes.hpp"
#include "laz_error.hpp"

#include <cstring>

namespace terratin::io::laz {

namespace {

/// Bytes of the POINT14 item, the first of every layered record.
constexpr std::size_t kPoint14Size = 30;

void checkVersion(const Item& item, std::string_view fileName) {
    // LASzip reads version 2, which its LAS 1.4 prototype wrote, as version 3.
    if (item.version == 2 || item.version == 3)
        return;
    const std::string name = itemName(static_cast<std::uint16_t>(item.type)) + " version " +
                             std::to_string(item.version);
    if (item.version == 0)
        throwInvalidLaz(fileName, name + " means stored uncompressed, which LASzip does not "
                                         "decode inside a compressed point stream");
    if (item.version == 4)
        throwInvalidLaz(fileName, name + " is not supported by this LAZ decoder (it decodes "
                                         "version 3; version 4 comes with LAS 1.5)");
    throwInvalidLaz(fileName, name + " is not supported by this LAZ decoder (it decodes "
                                     "version 3)");
}

[[noreturn]] void notLayered(const Item& item, std::size_t index, std::string_view fileName) {
    throwInvalidLaz(fileName, "item " + std::to_string(index + 1) + " is " +
                                  itemName(static_cast<std::uint16_t>(item.type)) +
                                  ", but the layered compressor (3) stores POINT14 first, then "
                                  "only RGB14, RGBNIR14, BYTE14 or WAVEPACKET14");
}

LayeredItemDecoder makeItemDecoder(const Item& item, std::size_t index, std::string_view fileName,
                                   bool wanted) {
    checkVersion(item, fileName);
    switch (item.type) {
    case ItemType::Rgb14:
        return LayeredItemDecoder(std::in_place_type<Rgb14V3Decoder>, false, wanted);
    case ItemType::RgbNir14:
        return LayeredItemDecoder(std::in_place_type<Rgb14V3Decoder>, true, wanted);
    case ItemType::Byte14:
        return LayeredItemDecoder(std::in_place_type<Byte14V3Decoder>, item.size, wanted);
    case ItemType::WavePacket14:
        return LayeredItemDecoder(std::in_place_type<WavePacket14V3Decoder>, wanted);
    default:
        notLayered(item, index, fileName);
    }
}

Point14V3Decoder::LayerSet point14Layers(FieldSelection fields) {
    Point14V3Decoder::LayerSet wanted;
    if (fields == FieldSelection::Every) {
        wanted.set();
        return wanted;
    }
    // What a TIN is built from: x, y and the returns (the first layer, always decoded), z,
    // classification and the flags (withheld). No context of these looks at another layer.
    wanted.set(Point14V3Decoder::kChannelReturnsXy);
    wanted.set(Point14V3Decoder::kZ);
    wanted.set(Point14V3Decoder::kClassification);
    wanted.set(Point14V3Decoder::kFlags);
    return wanted;
}

} // namespace

LayeredChunkDecoder::LayeredChunkDecoder(const LaszipRecord& record, std::string_view fileName,
                                         FieldSelection fields)
    : m_fileName(fileName), m_recordLength(record.recordLength()),
      m_decodeItems(fields == FieldSelection::Every), m_point(point14Layers(fields)) {
    // The LASzip record lists at least one item (parseLaszipRecord checks).
    if (record.items.front().type != ItemType::Point14)
        notLayered(record.items.front(), 0, fileName);
    checkVersion(record.items[0], fileName);
    m_layerCount = Point14V3Decoder::kLayerCount;
    std::size_t offset = kPoint14Size;
    for (std::size_t i = 1; i < record.items.size(); ++i) {
        const Item& item = record.items[i];
        PlacedItem placed{makeItemDecoder(item, i, fileName, m_decodeItems), offset, m_layerCount,
                          0};
        placed.layerCount =
            std::visit([](const auto& d) { return d.layerCount(); }, placed.decoder);
        m_layerCount += placed.layerCount;
        offset += item.size;
        m_items.push_back(std::move(placed));
    }
    m_layerBytes.resize(m_layerCount);
    m_firstRecord.resize(m_recordLength);
}

void LayeredChunkDecoder::start(std::span<const std::byte> chunk, std::uint64_t pointCount,
                                std::string label, std::byte* first) {
    m_label = std::move(label);
    m_pointCount = pointCount;
    splitLayers(chunk, pointCount);
    std::memcpy(m_firstRecord.data(), chunk.data(), m_recordLength);
    std::memcpy(first, chunk.data(), m_recordLength);
    startItems(m_firstRecord.data());
}

void LayeredChunkDecoder::splitLayers(std::span<const std::byte> chunk, std::uint64_t pointCount) {
    const std::size_t sizesAt = m_recordLength + 4;
    const std::size_t layersAt = sizesAt + 4 * m_layerCount;
    if (chunk.size() < layersAt)
        fail("is truncated or corrupt: its " + std::to_string(chunk.size()) +
             " bytes end before its first record, point count and " + std::to_string(m_layerCount) +
             " layer sizes (" + std::to_string(layersAt) + " bytes)");
    const auto count = loadLe<std::uint32_t>(chunk.data() + m_recordLength);
    if (count != pointCount)
        fail("is corrupt: it says it holds " + std::to_string(count) + " points, the chunk table " +
             std::to_string(pointCount));
    std::size_t at = layersAt;
    for (std::size_t i = 0; i < m_layerCount; ++i) {
        const auto size = loadLe<std::uint32_t>(chunk.data() + sizesAt + 4 * i);
        if (size > chunk.size() - at)
            fail("is truncated or corrupt: its layer sizes add up to more than its " +
                 std::to_string(chunk.size()) + " bytes (layer " + std::to_string(i + 1) + " of " +
                 std::to_string(m_layerCount) + ", " + std::to_string(size) +
                 " bytes, would end at byte " + std::to_string(at + size) + ")");
        m_layerBytes[i] = chunk.subspan(at, size);
        at += size;
    }
    m_chunkBytes = at;
}

void LayeredChunkDecoder::startItems(const std::byte* first) {
    const std::span<const std::span<const std::byte>> layers(m_layerBytes);
    m_point.start(first, layers.first(Point14V3Decoder::kLayerCount));
    const std::size_t context = m_point.itemContext();
    for (PlacedItem& item : m_items) {
        const auto itemLayers = layers.subspan(item.firstLayer, item.layerCount);
        std::visit([&](auto& d) { d.start(first + item.offset, itemLayers, context); },
                   item.decoder);
    }
}

void LayeredChunkDecoder::decode(std::span<std::byte> records) {
    std::byte* const end = records.data() + records.size();
    const std::size_t tail = m_recordLength - kPoint14Size;
    for (std::byte* record = records.data(); record != end; record += m_recordLength) {
        m_point.decode(record);
        if (!m_decodeItems) {
            if (tail != 0)
                std::memcpy(record + kPoint14Size, m_firstRecord.data() + kPoint14Size, tail);
            continue;
        }
        const std::size_t context = m_point.itemContext();
        for (PlacedItem& item : m_items) {
            std::byte* const field = record + item.offset;
            std::visit([&](auto& d) { d.decode(field, context); }, item.decoder);
        }
    }
    checkLayers();
}

void LayeredChunkDecoder::checkLayers() const {
    const auto check = [this](std::span<const LayerStream> layers) {
        for (const LayerStream& layer : layers) {
            if (layer.fault() == StreamFault::Truncated)
                fail("is truncated or corrupt: its " + layer.name() + " layer (" +
                     std::to_string(layer.size()) + " bytes) ends before its " +
                     std::to_string(m_pointCount) + " points do");
            if (layer.fault() == StreamFault::Corrupt)
                fail("is corrupt: its " + layer.name() +
                     " layer holds a value no LASzip writer produces");
        }
    };
    check(m_point.layers());
    for (const PlacedItem& item : m_items)
        std::visit([&](const auto& d) { check(d.layers()); }, item.decoder);
}

void LayeredChunkDecoder::fail(const std::string& what) const {
    throwInvalidLaz(m_fileName, m_label + " " + what);
}

} // namespace terratin::io::laz

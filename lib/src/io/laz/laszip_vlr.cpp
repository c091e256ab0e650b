/// @file
/// Parsing and checking of the LASzip VLR (layout in laszip_vlr.hpp). The accepted item
/// sizes and versions are those the LASzip format defines; anything else is rejected here,
/// before any point data is touched.

#include "laszip_vlr.hpp"

#include "laz_bytes.hpp"
#include "laz_error.hpp"

#include <array>

namespace terratin::io::laz {

namespace {

/// Bytes of the VLR before the item list, and per item.
constexpr std::size_t kFixedPart = 34;
constexpr std::size_t kItemEntry = 6;

constexpr std::array<std::string_view, 15> kItemNames{
    "BYTE",  "SHORT",        "INT",     "LONG",  "FLOAT",    "DOUBLE",       "POINT10", "GPSTIME11",
    "RGB12", "WAVEPACKET13", "POINT14", "RGB14", "RGBNIR14", "WAVEPACKET14", "BYTE14"};

/// What the format allows for one item type: a fixed size (0: any size of at least 1 byte)
/// and a bit set of the defined versions. SHORT .. DOUBLE (types 1-5) are named by the format
/// but never written, and no LASzip reads them.
struct ItemRule {
    bool known;
    std::uint16_t size;
    std::uint32_t versions;
    std::string_view versionText;
};

constexpr std::uint32_t kVersions0To1 = 0b11;
constexpr std::uint32_t kVersions0To2 = 0b111;
/// The LAS 1.4 items: 0 raw, 2 (written by a prototype), 3, and 4 (a later fix).
constexpr std::uint32_t kVersionsLas14 = 0b11101;
constexpr std::uint32_t kVersionsWave14 = 0b11001;
constexpr ItemRule kUnwritten{false, 0, 0, ""};

constexpr std::array<ItemRule, 15> kItemRules{{
    {true, 0, kVersions0To2, "0-2"}, // BYTE
    kUnwritten,
    kUnwritten,
    kUnwritten,
    kUnwritten,
    kUnwritten,
    {true, 20, kVersions0To2, "0-2"},         // POINT10
    {true, 8, kVersions0To2, "0-2"},          // GPSTIME11
    {true, 6, kVersions0To2, "0-2"},          // RGB12
    {true, 29, kVersions0To1, "0-1"},         // WAVEPACKET13
    {true, 30, kVersionsLas14, "0, 2, 3, 4"}, // POINT14
    {true, 6, kVersionsLas14, "0, 2, 3, 4"},  // RGB14
    {true, 8, kVersionsLas14, "0, 2, 3, 4"},  // RGBNIR14
    {true, 29, kVersionsWave14, "0, 3, 4"},   // WAVEPACKET14
    {true, 0, kVersionsLas14, "0, 2, 3, 4"},  // BYTE14
}};

void checkItem(const Item& item, std::size_t index, std::string_view fileName) {
    const auto rawType = static_cast<std::uint16_t>(item.type);
    const std::string where = "item " + std::to_string(index + 1) + " of the LASzip record: ";
    if (rawType >= kItemRules.size() || !kItemRules[rawType].known)
        throwInvalidLaz(fileName, where + "item type " + std::to_string(rawType) +
                                      " is unknown (LASzip defines the point item types 0 and "
                                      "6-14)");
    const ItemRule& rule = kItemRules[rawType];
    const std::string name = itemName(rawType);
    if (rule.size != 0 && item.size != rule.size)
        throwInvalidLaz(fileName, where + name + " has size " + std::to_string(item.size) +
                                      ", but the format fixes it at " + std::to_string(rule.size) +
                                      " bytes");
    if (rule.size == 0 && item.size == 0)
        throwInvalidLaz(fileName, where + name + " has size 0 (at least 1 byte)");
    if (item.version >= 32 || (rule.versions & (1u << item.version)) == 0)
        throwInvalidLaz(fileName, where + name + " version " + std::to_string(item.version) +
                                      " is unknown (LASzip defines " +
                                      std::string(rule.versionText) + ")");
}

void checkCompression(const LaszipRecord& record, std::string_view fileName) {
    const auto compressor = static_cast<std::uint16_t>(record.compressor);
    if (compressor > 3)
        throwInvalidLaz(fileName, "compressor " + std::to_string(compressor) +
                                      " is unknown (LASzip defines 0 none, 1 pointwise, "
                                      "2 pointwise chunked, 3 layered chunked)");
    if (record.coder != 0)
        throwInvalidLaz(fileName, "coder " + std::to_string(record.coder) +
                                      " is not the arithmetic coder (0), the only one LASzip "
                                      "defines");
}

} // namespace

std::string itemName(std::uint16_t type) {
    if (type < kItemNames.size())
        return std::string(kItemNames[type]);
    return "type " + std::to_string(type);
}

std::uint32_t LaszipRecord::recordLength() const {
    std::uint32_t length = 0;
    for (const Item& item : items)
        length += item.size;
    return length;
}

LaszipRecord parseLaszipRecord(std::span<const std::byte> payload, std::string_view fileName) {
    if (payload.size() < kFixedPart)
        throwInvalidLaz(fileName, "the LASzip record has " + std::to_string(payload.size()) +
                                      " bytes, fewer than the 34 of its fixed part");
    ByteCursor cursor(payload);
    LaszipRecord record;
    record.compressor = static_cast<Compressor>(cursor.read<std::uint16_t>());
    record.coder = cursor.read<std::uint16_t>();
    record.versionMajor = cursor.read<std::uint8_t>();
    record.versionMinor = cursor.read<std::uint8_t>();
    record.versionRevision = cursor.read<std::uint16_t>();
    record.options = cursor.read<std::uint32_t>();
    record.chunkSize = cursor.read<std::uint32_t>();
    record.specialEvlrCount = cursor.read<std::int64_t>();
    record.specialEvlrOffset = cursor.read<std::int64_t>();
    const auto itemCount = cursor.read<std::uint16_t>();
    checkCompression(record, fileName);
    if (itemCount == 0)
        throwInvalidLaz(fileName, "the LASzip record lists no items");
    const std::size_t expected = kFixedPart + kItemEntry * itemCount;
    if (payload.size() < expected)
        throwInvalidLaz(fileName, "the LASzip record lists " + std::to_string(itemCount) +
                                      " items, which need " + std::to_string(expected) +
                                      " bytes, but it has " + std::to_string(payload.size()));
    record.items.reserve(itemCount);
    for (std::size_t i = 0; i < itemCount; ++i) {
        Item item;
        item.type = static_cast<ItemType>(cursor.read<std::uint16_t>());
        item.size = cursor.read<std::uint16_t>();
        item.version = cursor.read<std::uint16_t>();
        checkItem(item, i, fileName);
        record.items.push_back(item);
    }
    return record;
}

} // namespace terratin::io::laz

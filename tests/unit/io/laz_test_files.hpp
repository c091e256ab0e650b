#pragma once
/// @file
/// Helpers of the LAZ decoder tests: the shared LAZ files (TERRATIN_SHARED_DEMS/laz, read in
/// place, never copied), the point records of their uncompressed LAS twins, whole-file
/// decoding through the chunk API, and a record comparison that names the first point and
/// field that differ.

#include "chunk_decoder.hpp"
#include "laz_bytes.hpp"
#include "laz_file.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <optional>
#include <string>
#include <vector>

namespace terratin::io::laz::test {

inline std::filesystem::path sharedLaz(const std::string& name) {
    return std::filesystem::path(TERRATIN_SHARED_DEMS) / "laz" / name;
}

inline std::filesystem::path sharedDem(const std::string& name) {
    return std::filesystem::path(TERRATIN_SHARED_DEMS) / name;
}

inline std::vector<std::byte> fileBytes(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    const std::vector<char> chars((std::istreambuf_iterator<char>(in)),
                                  std::istreambuf_iterator<char>());
    std::vector<std::byte> bytes(chars.size());
    for (std::size_t i = 0; i < chars.size(); ++i)
        bytes[i] = static_cast<std::byte>(chars[i]);
    return bytes;
}

/// The point records of an uncompressed LAS file, read by hand from its header (LAS 1.4 R15
/// 2.4: offset to point data at byte 96, format 104, record length 105, count 107 or, in
/// 1.4, 247).
struct LasRecords {
    int pointFormat = 0;
    std::size_t recordLength = 0;
    std::uint64_t count = 0;
    std::vector<std::byte> bytes;
};

inline LasRecords lasRecords(const std::filesystem::path& path) {
    const std::vector<std::byte> file = fileBytes(path);
    LasRecords records;
    const auto offset = loadLe<std::uint32_t>(file.data() + 96);
    records.pointFormat = loadLe<std::uint8_t>(file.data() + 104) & 0x3F;
    records.recordLength = loadLe<std::uint16_t>(file.data() + 105);
    records.count = loadLe<std::uint32_t>(file.data() + 107);
    if (loadLe<std::uint8_t>(file.data() + 25) >= 4 &&
        loadLe<std::uint64_t>(file.data() + 247) != 0)
        records.count = loadLe<std::uint64_t>(file.data() + 247);
    const std::size_t size = records.recordLength * static_cast<std::size_t>(records.count);
    records.bytes.assign(file.begin() + offset, file.begin() + offset + static_cast<long>(size));
    return records;
}

/// Every point of `file`, chunk by chunk, as LAS records (`fields` of them); checks on the way
/// that each chunk used exactly the bytes the chunk table gives it.
inline std::vector<std::byte> decodeAll(const LazFile& file,
                                        FieldSelection fields = FieldSelection::Every) {
    ChunkDecoder decoder(file.laszip(), file.name(), fields);
    const std::size_t length = file.header().recordLength;
    std::vector<std::byte> records(length * static_cast<std::size_t>(file.header().pointCount));
    std::vector<std::byte> bytes;
    for (std::size_t i = 0; i < file.chunks().size(); ++i) {
        const LazChunk& chunk = file.chunks()[i];
        file.readChunk(i, bytes);
        const std::span<std::byte> out(records.data() + chunk.firstPoint * length,
                                       static_cast<std::size_t>(chunk.pointCount) * length);
        const std::size_t used = decoder.decode(bytes, chunk.pointCount, out, file.chunkLabel(i));
        if (file.laszip().chunked()) {
            EXPECT_EQ(used, chunk.byteCount) << file.chunkLabel(i) << " of " << file.name();
        }
    }
    return records;
}

/// The field of a point record of format `format` (6-10) holding byte `at`.
inline std::string fieldAtLas14(int format, std::size_t at) {
    static const std::array<std::pair<std::size_t, const char*>, 12> base{{{0, "x"},
                                                                           {4, "y"},
                                                                           {8, "z"},
                                                                           {12, "intensity"},
                                                                           {14, "return byte"},
                                                                           {15, "flag byte"},
                                                                           {16, "classification"},
                                                                           {17, "user data"},
                                                                           {18, "scan angle"},
                                                                           {20, "point source id"},
                                                                           {22, "gps time"},
                                                                           {30, ""}}};
    for (std::size_t i = 0; i + 1 < base.size(); ++i)
        if (at < base[i + 1].first)
            return base[i].second;
    std::size_t rest = at - 30;
    if (format == 7 || format == 8 || format == 10) {
        const std::size_t colours = format == 7 ? 3 : 4;
        if (rest < 2 * colours)
            return std::array<const char*, 4>{"red", "green", "blue", "nir"}[rest / 2];
        rest -= 2 * colours;
    }
    if (format == 9 || format == 10) {
        if (rest < 29)
            return "wave packet";
        rest -= 29;
    }
    return "extra byte " + std::to_string(rest);
}

/// The field of a point record of format `format` (0-10) holding byte `at`.
inline std::string fieldAt(int format, std::size_t at) {
    if (format >= 6)
        return fieldAtLas14(format, at);
    static const std::array<std::pair<std::size_t, const char*>, 10> base{{{0, "x"},
                                                                           {4, "y"},
                                                                           {8, "z"},
                                                                           {12, "intensity"},
                                                                           {14, "return byte"},
                                                                           {15, "class byte"},
                                                                           {16, "scan angle"},
                                                                           {17, "user data"},
                                                                           {18, "point source id"},
                                                                           {20, ""}}};
    for (std::size_t i = 0; i + 1 < base.size(); ++i)
        if (at < base[i + 1].first)
            return base[i].second;
    std::size_t rest = at - 20;
    const bool time = format == 1 || format == 3 || format == 4 || format == 5;
    const bool colour = format == 2 || format == 3 || format == 5;
    if (time) {
        if (rest < 8)
            return "gps time";
        rest -= 8;
    }
    if (colour) {
        if (rest < 6)
            return std::array<const char*, 3>{"red", "green", "blue"}[rest / 2];
        rest -= 6;
    }
    return "extra byte " + std::to_string(rest);
}

/// Empty when `actual` equals `expected`; else the first point and field that differ.
inline std::optional<std::string> firstDifference(const std::vector<std::byte>& actual,
                                                  const std::vector<std::byte>& expected,
                                                  std::size_t recordLength, int format) {
    if (actual.size() != expected.size())
        return "sizes differ: " + std::to_string(actual.size()) + " vs " +
               std::to_string(expected.size()) + " bytes";
    for (std::size_t i = 0; i < actual.size(); ++i) {
        if (actual[i] != expected[i]) {
            const std::size_t point = i / recordLength;
            return "point " + std::to_string(point) + " (of " +
                   std::to_string(actual.size() / recordLength) + ") differs first in its " +
                   fieldAt(format, i % recordLength) + " (record byte " +
                   std::to_string(i % recordLength) + ": " +
                   std::to_string(std::to_integer<int>(actual[i])) + ", expected " +
                   std::to_string(std::to_integer<int>(expected[i])) + ")";
        }
    }
    return std::nullopt;
}

} // namespace terratin::io::laz::test

#include "las_test_file.hpp"

#include <cstring>
#include <stdexcept>

namespace terratin::test {

namespace {

template <typename T> void put(std::vector<std::byte>& out, std::size_t pos, T value) {
    if (out.size() < pos + sizeof(T))
        out.resize(pos + sizeof(T));
    std::memcpy(out.data() + pos, &value, sizeof(T));
}

void putText(std::vector<std::byte>& out, std::size_t pos, const std::string& text,
             std::size_t width) {
    for (std::size_t i = 0; i < width; ++i)
        put<char>(out, pos + i, i < text.size() ? text[i] : '\0');
}

} // namespace

template <typename T> void poke(std::vector<std::byte>& bytes, std::size_t pos, T value) {
    put(bytes, pos, value);
}
template void poke<std::uint8_t>(std::vector<std::byte>&, std::size_t, std::uint8_t);
template void poke<std::uint16_t>(std::vector<std::byte>&, std::size_t, std::uint16_t);
template void poke<std::uint32_t>(std::vector<std::byte>&, std::size_t, std::uint32_t);
template void poke<std::uint64_t>(std::vector<std::byte>&, std::size_t, std::uint64_t);
template void poke<double>(std::vector<std::byte>&, std::size_t, double);

std::uint16_t lasMinimumRecordLength(int pointFormat) {
    static constexpr std::uint16_t kLengths[] = {20, 28, 26, 34, 57, 63, 30, 36, 38, 59, 67};
    if (pointFormat < 0 || pointFormat > 10)
        throw std::invalid_argument("point format outside 0..10");
    return kLengths[pointFormat];
}

std::vector<std::byte> LasTestFile::bytes() const {
    const std::uint16_t headerSize = versionMinor >= 4 ? 375 : versionMinor == 3 ? 235 : 227;
    const auto recordLength =
        static_cast<std::uint16_t>(lasMinimumRecordLength(pointFormat) + extraRecordBytes);
    std::size_t vlrBytes = 0;
    for (const LasTestRecord& vlr : vlrs)
        vlrBytes += 54 + vlr.data.size();
    const std::size_t pointOffset = headerSize + vlrBytes;

    std::vector<std::byte> out(pointOffset + points.size() * recordLength);
    putText(out, 0, "LASF", 4);
    put<std::uint16_t>(out, 6, wktBit ? 0x10 : 0);
    put<std::uint8_t>(out, 24, 1);
    put<std::uint8_t>(out, 25, static_cast<std::uint8_t>(versionMinor));
    putText(out, 26, "terratin test", 32);
    putText(out, 58, "las_test_file", 32);
    put<std::uint16_t>(out, 94, headerSize);
    put<std::uint32_t>(out, 96, static_cast<std::uint32_t>(pointOffset));
    put<std::uint32_t>(out, 100, static_cast<std::uint32_t>(vlrs.size()));
    put<std::uint8_t>(out, 104, static_cast<std::uint8_t>(pointFormat));
    put<std::uint16_t>(out, 105, recordLength);
    put<std::uint32_t>(out, 107, static_cast<std::uint32_t>(points.size()));
    for (std::size_t axis = 0; axis < 3; ++axis) {
        put<double>(out, 131 + 8 * axis, scale[axis]);
        put<double>(out, 155 + 8 * axis, offset[axis]);
    }
    if (versionMinor >= 4)
        put<std::uint64_t>(out, 247, points.size());

    std::size_t pos = headerSize;
    for (const LasTestRecord& vlr : vlrs) {
        putText(out, pos + 2, vlr.userId, 16);
        put<std::uint16_t>(out, pos + 18, vlr.recordId);
        put<std::uint16_t>(out, pos + 20, static_cast<std::uint16_t>(vlr.data.size()));
        if (!vlr.data.empty())
            std::memcpy(out.data() + pos + 54, vlr.data.data(), vlr.data.size());
        pos += 54 + vlr.data.size();
    }

    const bool extended = pointFormat >= 6;
    for (const LasTestPoint& p : points) {
        put<std::int32_t>(out, pos, p.x);
        put<std::int32_t>(out, pos + 4, p.y);
        put<std::int32_t>(out, pos + 8, p.z);
        if (extended) {
            put<std::uint8_t>(
                out, pos + 14,
                static_cast<std::uint8_t>((p.returnNumber & 0x0F) | ((p.returnCount & 0x0F) << 4)));
            put<std::uint8_t>(out, pos + 15, static_cast<std::uint8_t>(p.withheld ? 0x04 : 0));
            put<std::uint8_t>(out, pos + 16, p.classification);
        } else {
            put<std::uint8_t>(
                out, pos + 14,
                static_cast<std::uint8_t>((p.returnNumber & 0x07) | ((p.returnCount & 0x07) << 3)));
            put<std::uint8_t>(
                out, pos + 15,
                static_cast<std::uint8_t>((p.classification & 0x1F) | (p.withheld ? 0x80 : 0)));
        }
        pos += recordLength;
    }

    if (versionMinor >= 4 && !evlrs.empty()) {
        put<std::uint64_t>(out, 235, out.size());
        put<std::uint32_t>(out, 243, static_cast<std::uint32_t>(evlrs.size()));
        for (const LasTestRecord& evlr : evlrs) {
            const std::size_t at = out.size();
            out.resize(at + 60 + evlr.data.size());
            putText(out, at + 2, evlr.userId, 16);
            put<std::uint16_t>(out, at + 18, evlr.recordId);
            put<std::uint64_t>(out, at + 20, evlr.data.size());
            if (!evlr.data.empty())
                std::memcpy(out.data() + at + 60, evlr.data.data(), evlr.data.size());
        }
    }
    return out;
}

LasTestRecord geoKeysForProjectedEpsg(std::uint16_t epsg) {
    // GeoTIFF 1.0: header {1, 1, 0, keys}, then {key, location 0 (value inline), 1, value}.
    const std::uint16_t keys[] = {1,    1, 0, 3, //
                                  1024, 0, 1, 1, // GTModelTypeGeoKey = projected
                                  1025, 0, 1, 1, // GTRasterTypeGeoKey = PixelIsArea
                                  3072, 0, 1, epsg};
    LasTestRecord record{"LASF_Projection", 34735, {}};
    record.data.resize(sizeof keys);
    std::memcpy(record.data.data(), keys, sizeof keys);
    return record;
}

LasTestRecord wktRecord(const std::string& wkt) {
    LasTestRecord record{"LASF_Projection", 2112, {}};
    record.data.resize(wkt.size() + 1);
    std::memcpy(record.data.data(), wkt.c_str(), wkt.size() + 1);
    return record;
}

} // namespace terratin::test

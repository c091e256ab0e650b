/// @file
/// GeoTIFF keys to WKT through GDAL's GeoTIFF driver.
///
/// The TIFF written here is the smallest baseline file GDAL accepts (TIFF 6.0, section 2:
/// one 8-bit grey pixel in one strip) plus the three GeoTIFF tags (GeoTIFF 1.0, section 2.4):
/// 34735 GeoKeyDirectoryTag (SHORT), 34736 GeoDoubleParamsTag (DOUBLE), 34737
/// GeoAsciiParamsTag (ASCII). Little-endian throughout.

#include "geotiff_keys.hpp"

#include "../crs/wkt.hpp"
#include "terratin/error.hpp"
#include "terratin/gdal_error.hpp"

#include <cpl_conv.h>
#include <cpl_vsi.h>
#include <gdal.h>
#include <ogr_spatialref.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <bit>
#include <cstring>
#include <memory>
#include <vector>

namespace terratin::io::detail {

namespace {

static_assert(std::endian::native == std::endian::little,
              "the TIFF written here and the LAS reader assume a little-endian machine");

enum TiffType : std::uint16_t { kAscii = 2, kShort = 3, kLong = 4, kDouble = 12 };

struct TiffEntry {
    std::uint16_t tag;
    std::uint16_t type;
    std::uint32_t count;
    std::vector<std::byte> payload; // the value bytes, inline when 4 bytes or fewer
};

template <typename T> void append(std::vector<std::byte>& out, const T& value) {
    const std::size_t at = out.size();
    out.resize(at + sizeof(T));
    std::memcpy(out.data() + at, &value, sizeof(T));
}

template <typename T> std::vector<std::byte> bytesOf(std::span<const T> values) {
    std::vector<std::byte> out(values.size_bytes());
    if (!values.empty())
        std::memcpy(out.data(), values.data(), values.size_bytes());
    return out;
}

TiffEntry shortEntry(std::uint16_t tag, std::uint16_t value) {
    return {tag, kShort, 1, bytesOf(std::span<const std::uint16_t>(&value, 1))};
}

TiffEntry longEntry(std::uint16_t tag, std::uint32_t value) {
    return {tag, kLong, 1, bytesOf(std::span<const std::uint32_t>(&value, 1))};
}

/// Serialises a one-IFD little-endian TIFF whose strip is one byte; the StripOffsets entry
/// (tag 273) is patched to point at that byte.
std::vector<std::byte> serialiseTiff(std::vector<TiffEntry> entries) {
    std::sort(entries.begin(), entries.end(),
              [](const TiffEntry& a, const TiffEntry& b) { return a.tag < b.tag; });
    const std::size_t ifdSize = 2 + 12 * entries.size() + 4;
    std::size_t dataOffset = 8 + ifdSize;
    // Out-of-line payloads follow the IFD, each on an 8-byte boundary (DOUBLEs like that).
    std::vector<std::uint32_t> payloadOffsets(entries.size(), 0);
    for (std::size_t i = 0; i < entries.size(); ++i) {
        if (entries[i].payload.size() <= 4)
            continue;
        dataOffset = (dataOffset + 7) / 8 * 8;
        payloadOffsets[i] = static_cast<std::uint32_t>(dataOffset);
        dataOffset += entries[i].payload.size();
    }
    const auto pixelOffset = static_cast<std::uint32_t>(dataOffset);
    for (TiffEntry& entry : entries)
        if (entry.tag == 273)
            entry.payload = bytesOf(std::span<const std::uint32_t>(&pixelOffset, 1));

    std::vector<std::byte> out;
    out.reserve(dataOffset + 1);
    append(out, std::uint16_t{0x4949}); // "II": little-endian
    append(out, std::uint16_t{42});
    append(out, std::uint32_t{8});
    append(out, static_cast<std::uint16_t>(entries.size()));
    for (std::size_t i = 0; i < entries.size(); ++i) {
        const TiffEntry& entry = entries[i];
        append(out, entry.tag);
        append(out, entry.type);
        append(out, entry.count);
        if (entry.payload.size() <= 4) {
            std::array<std::byte, 4> inlineValue{};
            std::copy(entry.payload.begin(), entry.payload.end(), inlineValue.begin());
            append(out, inlineValue);
        } else {
            append(out, payloadOffsets[i]);
        }
    }
    append(out, std::uint32_t{0}); // no next IFD
    for (std::size_t i = 0; i < entries.size(); ++i) {
        if (payloadOffsets[i] == 0)
            continue;
        out.resize(payloadOffsets[i] + entries[i].payload.size(), std::byte{0});
        std::memcpy(out.data() + payloadOffsets[i], entries[i].payload.data(),
                    entries[i].payload.size());
    }
    out.resize(pixelOffset, std::byte{0});
    out.push_back(std::byte{0}); // the pixel
    return out;
}

struct DatasetCloser {
    void operator()(void* dataset) const { GDALClose(dataset); }
};

} // namespace

namespace {

/// The keys of `directory` (GeoTIFF 1.0, 2.4: a header of four SHORTs, version 1, revision,
/// minor revision and number of keys, then four SHORTs per key), the header checked; CrsError
/// starting with `where` otherwise.
std::span<const std::uint16_t> keysOf(std::span<const std::uint16_t> directory,
                                      const std::string& where) {
    if (directory.size() < 4)
        throw CrsError(where + "the GeoTIFF key directory is shorter than its header");
    if (directory[0] != 1)
        throw CrsError(where + "GeoTIFF key directory version " + std::to_string(directory[0]) +
                       " (only 1 exists)");
    const std::size_t keys = directory[3];
    if (directory.size() < 4 * (keys + 1))
        throw CrsError(where + "the GeoTIFF key directory declares " + std::to_string(keys) +
                       " keys but holds " + std::to_string(directory.size() / 4 - 1));
    if (keys == 0)
        throw CrsError(where + "the GeoTIFF key directory holds no key");
    return directory.first(4 * (keys + 1));
}

/// The tags of a one-pixel TIFF that carries the GeoTIFF keys `used` and their parameters.
std::vector<TiffEntry> geoKeyEntries(std::span<const std::uint16_t> used,
                                     std::span<const double> doubleParams,
                                     std::string_view asciiParams) {
    std::vector<TiffEntry> entries{shortEntry(256, 1), shortEntry(257, 1), shortEntry(258, 8),
                                   shortEntry(259, 1), shortEntry(262, 1), longEntry(273, 0),
                                   shortEntry(277, 1), shortEntry(278, 1), longEntry(279, 1),
                                   shortEntry(284, 1)};
    entries.push_back({34735, kShort, static_cast<std::uint32_t>(used.size()), bytesOf(used)});
    if (!doubleParams.empty())
        entries.push_back({34736, kDouble, static_cast<std::uint32_t>(doubleParams.size()),
                           bytesOf(doubleParams)});
    if (!asciiParams.empty()) {
        // ASCII values are NUL-terminated; LAS writers do not always include the terminator.
        std::string ascii(asciiParams);
        if (ascii.back() != '\0')
            ascii.push_back('\0');
        entries.push_back({34737, kAscii, static_cast<std::uint32_t>(ascii.size()),
                           bytesOf(std::span<const char>(ascii.data(), ascii.size()))});
    }
    return entries;
}

/// The CRS GDAL's GeoTIFF reader finds in `tiff`, as WKT; empty when it finds none.
std::string crsOfTiff(std::vector<std::byte>& tiff, const std::string& where) {
    // A name no other call uses at the same time: /vsimem is process-wide.
    static std::atomic<std::uint64_t> counter{0};
    const std::string memName =
        "/vsimem/terratin_geokeys_" + std::to_string(counter.fetch_add(1)) + ".tif";
    initialiseGdal();
    VSILFILE* file = VSIFileFromMemBuffer(memName.c_str(), reinterpret_cast<GByte*>(tiff.data()),
                                          static_cast<vsi_l_offset>(tiff.size()), FALSE);
    if (file == nullptr)
        throw CrsError(where + "cannot create an in-memory TIFF for its GeoTIFF keys");
    VSIFCloseL(file);

    std::string wkt;
    {
        const char* const drivers[] = {"GTiff", nullptr};
        CPLErrorReset();
        const std::unique_ptr<void, DatasetCloser> dataset(
            GDALOpenEx(memName.c_str(), GDAL_OF_RASTER, drivers, nullptr, nullptr));
        if (dataset) {
            const auto* srs = OGRSpatialReference::FromHandle(GDALGetSpatialRef(dataset.get()));
            if (srs != nullptr)
                wkt = crs::detail::exportWkt(*srs);
        }
    }
    VSIUnlink(memName.c_str());
    return wkt;
}

} // namespace

std::string geoTiffKeysToWkt(std::span<const std::uint16_t> directory,
                             std::span<const double> doubleParams, std::string_view asciiParams,
                             std::string_view stage, std::string_view name) {
    const std::string where = std::string(stage) + ": '" + std::string(name) + "': ";
    const std::span<const std::uint16_t> used = keysOf(directory, where);
    std::vector<std::byte> tiff = serialiseTiff(geoKeyEntries(used, doubleParams, asciiParams));
    const std::string wkt = crsOfTiff(tiff, where);
    if (wkt.empty())
        throw CrsError(where + "its GeoTIFF keys describe no CRS GDAL can use: " +
                       lastGdalErrorMessage("GDAL derives no CRS from them"));
    return wkt;
}

std::string normaliseWkt(std::string_view wkt, std::string_view stage, std::string_view name) {
    // GDAL's error handler, terratin's, keeps its message for ours; its default one would print
    // an "ERROR 1:" line of its own before terratin's.
    initialiseGdal();
    OGRSpatialReference srs;
    const std::string text(wkt);
    if (srs.importFromWkt(text.c_str()) != OGRERR_NONE)
        throw CrsError(std::string(stage) + ": '" + std::string(name) +
                       "': its WKT CRS record cannot be read: " +
                       lastGdalErrorMessage("it is not WKT GDAL can parse"));
    std::string out = crs::detail::exportWkt(srs);
    if (out.empty())
        throw CrsError(std::string(stage) + ": '" + std::string(name) +
                       "': its WKT CRS cannot be exported: " +
                       lastGdalErrorMessage("PROJ has no WKT1 or WKT2 form of it"));
    return out;
}

} // namespace terratin::io::detail

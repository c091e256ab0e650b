/// @file
/// LasReader: an own binary parser of ASPRS LAS 1.0-1.4 (uncompressed); the header and its
/// (E)VLRs are las_header.hpp's.
/// Which records are kept is las_record_filter.hpp's; LAZ (compressed records) is decoded by
/// laz/laz_points.hpp.
///
/// Every size the header declares is checked against the file size before anything is read
/// at it; all reads go through ByteSource::read, which is given checked ranges only.

#include "terratin/io/las_reader.hpp"

#include "geotiff_keys.hpp"
#include "las_header.hpp"
#include "las_record_filter.hpp"
#include "laz/laz_file.hpp"
#include "laz/laz_points.hpp"
#include "terratin/error.hpp"

#include <algorithm>
#include <array>
#include <bitset>
#include <cstring>
#include <string>
#include <vector>

namespace terratin::io {

using detail::classesKept;
using detail::CrsRecords;
using detail::LasRecordFilter;
using detail::ParsedHeader;
using detail::parseHeader;
using detail::trimmedText;

namespace {

constexpr std::string_view kStage = detail::kLasStage;

/// Point records per read: about 4 MiB of buffer whatever the record length, so memory stays
/// bounded and each fread is large enough to run at disk speed.
constexpr std::size_t kBufferBytes = std::size_t{4} << 20;

/// Global encoding bit 4: the CRS is WKT (1.4, table 4).
constexpr std::uint16_t kWktBit = 0x10;

template <typename T> std::vector<T> asArray(const std::vector<std::byte>& bytes) {
    std::vector<T> values(bytes.size() / sizeof(T));
    if (!values.empty())
        std::memcpy(values.data(), bytes.data(), values.size() * sizeof(T));
    return values;
}

std::string crsOf(const ParsedHeader& parsed, const std::string& name) {
    const CrsRecords& records = parsed.crs;
    const auto fromWkt = [&] {
        const std::string text = trimmedText(*records.wkt);
        return text.empty() ? std::string() : detail::normaliseWkt(text, kStage, name);
    };
    const auto fromGeoKeys = [&] {
        const std::vector<std::uint16_t> keys = asArray<std::uint16_t>(*records.geoKeys);
        const std::vector<double> doubles =
            records.geoDoubles ? asArray<double>(*records.geoDoubles) : std::vector<double>();
        const std::string ascii =
            records.geoAscii ? std::string(reinterpret_cast<const char*>(records.geoAscii->data()),
                                           records.geoAscii->size())
                             : std::string();
        return detail::geoTiffKeysToWkt(keys, doubles, ascii, kStage, name);
    };
    if ((parsed.header.globalEncoding & kWktBit) != 0 && records.wkt)
        return fromWkt();
    if (records.geoKeys)
        return fromGeoKeys();
    if (records.wkt)
        return fromWkt();
    return {};
}

PointCloud readPoints(const detail::ByteSource& source, const std::string& name,
                      const LasReadOptions& options, const ProgressCallback& progress) {
    const std::bitset<256> keepClass = classesKept(options); // refused before the header
    const ParsedHeader parsed = parseHeader(source, name);
    const LasHeader& h = parsed.header;
    const LasRecordFilter decoder(h, options.returns, keepClass);
    PointCloud cloud;
    cloud.path = name;
    cloud.kind = h.compressed ? InputKind::Laz : InputKind::Las;
    cloud.crsWkt = crsOf(parsed, name);
    cloud.recordsRead = h.pointCount;
    if (h.compressed) {
        const laz::LazFile file = laz::LazFile::fromParsedHeader(source, name, parsed);
        laz::readLazPoints(file, decoder, options.threads, progress, cloud);
        return cloud;
    }

    const std::size_t recordLength = h.recordLength;
    const std::size_t recordsPerBuffer = std::max<std::size_t>(1, kBufferBytes / recordLength);
    std::vector<std::byte> buffer(recordLength * static_cast<std::size_t>(std::min<std::uint64_t>(
                                                     recordsPerBuffer, h.pointCount)));
    // Bounded by the file size, already checked: 24 bytes per point for at most
    // fileSize / 20 records.
    cloud.points.reserve(static_cast<std::size_t>(h.pointCount));
    for (std::uint64_t first = 0; first < h.pointCount; first += recordsPerBuffer) {
        const auto records = static_cast<std::size_t>(
            std::min<std::uint64_t>(recordsPerBuffer, h.pointCount - first));
        const std::span<std::byte> chunk(buffer.data(), records * recordLength);
        source.read(h.pointDataOffset + first * recordLength, chunk);
        decoder.decode(chunk.data(), records, recordLength, cloud);
        if (progress) {
            const double fraction =
                static_cast<double>(first + records) / static_cast<double>(h.pointCount);
            if (!progress(fraction, "reading LAS"))
                throw Cancelled(std::string(kStage) + ": cancelled while reading '" + name + "'");
        }
    }
    if (cloud.points.size() * 4 < cloud.points.capacity())
        cloud.points.shrink_to_fit();
    return cloud;
}

} // namespace

PointCloud readLasPoints(const std::string& path, const LasReadOptions& options,
                         const ProgressCallback& progress) {
    const detail::FileSource source(path, kStage);
    return readPoints(source, path, options, progress);
}

PointCloud readLasPointsFromMemory(std::span<const std::byte> data, const std::string& name,
                                   const LasReadOptions& options,
                                   const ProgressCallback& progress) {
    const detail::MemorySource source(data);
    return readPoints(source, name, options, progress);
}

LasHeader readLasHeader(const std::string& path) {
    const detail::FileSource source(path, kStage);
    return detail::parseHeader(source, path).header;
}

} // namespace terratin::io

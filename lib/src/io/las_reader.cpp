/// @file
/// LasReader: an own binary parser of ASPRS LAS 1.0-1.4 (uncompressed); the header and its
/// (E)VLRs are las_header.hpp's.
///
/// Point records (LAS 1.4 R15, 2.6) begin with X, Y, Z as int32 and x = X * scale + offset.
/// Formats 0-5 pack return number / number of returns in 3 + 3 bits of byte 14 and the class
/// in the low 5 bits of byte 15 (withheld: bit 7); formats 6-10 use 4 + 4 bits in byte 14,
/// flags in byte 15 (withheld: bit 2) and a whole byte 16 for the class.
///
/// Every size the header declares is checked against the file size before anything is read
/// at it; all reads go through ByteSource::read, which is given checked ranges only.

#include "terratin/io/las_reader.hpp"

#include "geotiff_keys.hpp"
#include "las_header.hpp"
#include "terratin/error.hpp"

#include <algorithm>
#include <array>
#include <bitset>
#include <cstring>
#include <string>
#include <vector>

namespace terratin::io {

using detail::CrsRecords;
using detail::field;
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

/// The classes `options` keeps (all when it names none); InvalidInputError for a code outside
/// 0..255.
std::bitset<256> classesKept(const LasReadOptions& options) {
    std::bitset<256> keep;
    if (options.classes.empty())
        return keep.set();
    for (const int code : options.classes) {
        if (code < 0 || code > 255)
            throw InvalidInputError(std::string(kStage) + ": classification " +
                                    std::to_string(code) + " is outside 0..255");
        keep.set(static_cast<std::size_t>(code));
    }
    return keep;
}

/// Which point records a read keeps, and their coordinates: the per-point path, kept small
/// enough to be inlined into the loop over a buffer of records.
class RecordDecoder {
public:
    RecordDecoder(const LasHeader& h, LasReturns returns, const std::bitset<256>& keepClass)
        : m_keepClass(keepClass), m_returns(returns), m_extended(h.pointFormat >= 6),
          m_scale(h.scale), m_offset(h.offset) {}

    /// Whether `record` passes the filters: not withheld (the specification calls such points
    /// deleted), of a return and a class the options keep.
    [[nodiscard]] bool keeps(std::span<const std::byte> record) const {
        const auto returnByte = field<std::uint8_t>(record, 14);
        const auto flagByte = field<std::uint8_t>(record, 15);
        unsigned returnNumber = 0;
        unsigned returnCount = 0;
        unsigned classification = 0;
        bool withheld = false;
        if (m_extended) {
            returnNumber = returnByte & 0x0Fu;
            returnCount = (returnByte >> 4) & 0x0Fu;
            withheld = (flagByte & 0x04u) != 0;
            classification = field<std::uint8_t>(record, 16);
        } else {
            returnNumber = returnByte & 0x07u;
            returnCount = (returnByte >> 3) & 0x07u;
            withheld = (flagByte & 0x80u) != 0;
            classification = flagByte & 0x1Fu;
        }
        const bool returnKept = m_returns == LasReturns::All ||
                                (m_returns == LasReturns::First && returnNumber <= 1) ||
                                (m_returns == LasReturns::Last && returnNumber >= returnCount);
        return !withheld && returnKept && m_keepClass.test(classification);
    }

    /// x = X * scale + offset, the same for y and z.
    [[nodiscard]] Point3 point(std::span<const std::byte> record) const {
        const auto x = field<std::int32_t>(record, 0);
        const auto y = field<std::int32_t>(record, 4);
        const auto z = field<std::int32_t>(record, 8);
        return {x * m_scale[0] + m_offset[0], y * m_scale[1] + m_offset[1],
                z * m_scale[2] + m_offset[2]};
    }

    /// Appends to `cloud` the kept points of `records` records of `recordLength` bytes each
    /// at `chunk`, counting the others as filtered out.
    void decode(const std::byte* chunk, std::size_t records, std::size_t recordLength,
                PointCloud& cloud) const {
        for (std::size_t r = 0; r < records; ++r) {
            const std::span<const std::byte> record(chunk + r * recordLength, recordLength);
            if (keeps(record))
                cloud.points.push_back(point(record));
            else
                ++cloud.filteredOut;
        }
    }

private:
    std::bitset<256> m_keepClass;
    LasReturns m_returns;
    bool m_extended;
    std::array<double, 3> m_scale;
    std::array<double, 3> m_offset;
};

PointCloud readPoints(detail::ByteSource& source, const std::string& name,
                      const LasReadOptions& options, const ProgressCallback& progress) {
    const std::bitset<256> keepClass = classesKept(options); // refused before the header
    const ParsedHeader parsed = parseHeader(source, name);
    const LasHeader& h = parsed.header;
    const RecordDecoder decoder(h, options.returns, keepClass);
    PointCloud cloud;
    cloud.path = name;
    cloud.kind = InputKind::Las;
    cloud.crsWkt = crsOf(parsed, name);
    cloud.recordsRead = h.pointCount;

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
    detail::FileSource source(path);
    return readPoints(source, path, options, progress);
}

PointCloud readLasPointsFromMemory(std::span<const std::byte> data, const std::string& name,
                                   const LasReadOptions& options,
                                   const ProgressCallback& progress) {
    detail::MemorySource source(data);
    return readPoints(source, name, options, progress);
}

LasHeader readLasHeader(const std::string& path) {
    detail::FileSource source(path);
    return detail::parseHeader(source, path).header;
}

} // namespace terratin::io

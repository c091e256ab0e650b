/// @file
/// LasReader: an own binary parser of ASPRS LAS 1.0-1.4 (uncompressed).
///
/// Notation (LAS 1.4 R15, 2.4): the public header block is read at fixed byte offsets; 1.0-1.2
/// stop at byte 227, 1.3 adds the waveform offset (to 235), 1.4 the EVLR start and count and
/// the 64-bit point counts (to 375). Point records (2.6) begin with X, Y, Z as int32 and
/// x = X * scale + offset. Formats 0-5 pack return number / number of returns in 3 + 3 bits of
/// byte 14 and the class in the low 5 bits of byte 15 (withheld: bit 7); formats 6-10 use 4 + 4
/// bits in byte 14, flags in byte 15 (withheld: bit 2) and a whole byte 16 for the class.
///
/// Every size the header declares is checked against the file size before anything is read
/// at it; all reads go through ByteSource::read, which is given checked ranges only.

#include "terratin/io/las_reader.hpp"

#include "geotiff_keys.hpp"
#include "terratin/error.hpp"
#include "../text.hpp"

#include <algorithm>
#include <bitset>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <memory>
#include <optional>

namespace terratin::io {

using terratin::detail::lowercase;

namespace {

constexpr std::string_view kStage = "LasReader";

/// Point records per read: about 4 MiB of buffer whatever the record length, so memory stays
/// bounded and each fread is large enough to run at disk speed.
constexpr std::size_t kBufferBytes = std::size_t{4} << 20;

/// Bytes of the public header block by minor version (LAS 1.4 R15 table 3 and its ancestors).
constexpr std::uint16_t kHeaderSize12 = 227;
constexpr std::uint16_t kHeaderSize13 = 235;
constexpr std::uint16_t kHeaderSize14 = 375;
/// VLR and EVLR headers (2.5, 2.8).
constexpr std::uint64_t kVlrHeaderSize = 54;
constexpr std::uint64_t kEvlrHeaderSize = 60;
/// Minimum record length of point formats 0..10 (2.6, tables 7-17).
constexpr std::array<std::uint16_t, 11> kMinRecordLength{20, 28, 26, 34, 57, 63,
                                                         30, 36, 38, 59, 67};
/// Global encoding bit 4: the CRS is WKT (1.4, table 4).
constexpr std::uint16_t kWktBit = 0x10;

/// Reads whole byte ranges that the caller has checked against size().
class ByteSource {
public:
    virtual ~ByteSource() = default;
    [[nodiscard]] virtual std::uint64_t size() const = 0;
    /// Fills `out` from `offset`. Precondition: offset + out.size() <= size().
    virtual void read(std::uint64_t offset, std::span<std::byte> out) = 0;
};

class MemorySource final : public ByteSource {
public:
    explicit MemorySource(std::span<const std::byte> data) : m_data(data) {}
    [[nodiscard]] std::uint64_t size() const override { return m_data.size(); }
    void read(std::uint64_t offset, std::span<std::byte> out) override {
        if (!out.empty())
            std::memcpy(out.data(), m_data.data() + offset, out.size());
    }

private:
    std::span<const std::byte> m_data;
};

struct FileCloser {
    void operator()(std::FILE* file) const { std::fclose(file); }
};

class FileSource final : public ByteSource {
public:
    explicit FileSource(const std::string& path) : m_path(path) {
        m_file.reset(std::fopen(path.c_str(), "rb"));
        if (!m_file)
            throw IoError(std::string(kStage) + ": cannot open '" + path +
                          "': " + std::strerror(errno));
        if (fseeko(m_file.get(), 0, SEEK_END) != 0)
            throw IoError(std::string(kStage) + ": cannot seek in '" + path + "'");
        const off_t end = ftello(m_file.get());
        if (end < 0)
            throw IoError(std::string(kStage) + ": cannot size '" + path + "' (not a file?)");
        m_size = static_cast<std::uint64_t>(end);
        m_position = m_size;
    }
    [[nodiscard]] std::uint64_t size() const override { return m_size; }
    void read(std::uint64_t offset, std::span<std::byte> out) override {
        if (out.empty())
            return;
        if (offset != m_position && fseeko(m_file.get(), static_cast<off_t>(offset), SEEK_SET) != 0)
            throw IoError(std::string(kStage) + ": cannot seek in '" + m_path + "'");
        if (std::fread(out.data(), 1, out.size(), m_file.get()) != out.size())
            throw IoError(std::string(kStage) + ": cannot read " + std::to_string(out.size()) +
                          " bytes at offset " + std::to_string(offset) + " of '" + m_path +
                          "' (the file changed while being read?)");
        m_position = offset + out.size();
    }

private:
    std::string m_path;
    std::unique_ptr<std::FILE, FileCloser> m_file;
    std::uint64_t m_size = 0;
    std::uint64_t m_position = 0;
};

/// A little-endian field at `pos` of `bytes`; memcpy keeps it free of alignment and aliasing
/// problems. Precondition: pos + sizeof(T) <= bytes.size().
template <typename T> T field(std::span<const std::byte> bytes, std::size_t pos) {
    T value;
    std::memcpy(&value, bytes.data() + pos, sizeof(T));
    return value;
}

[[noreturn]] void invalid(const std::string& name, const std::string& what) {
    throw InvalidInputError(std::string(kStage) + ": '" + name + "': " + what);
}

std::string trimmedText(std::span<const std::byte> bytes) {
    std::string text(reinterpret_cast<const char*>(bytes.data()), bytes.size());
    const std::size_t end = text.find('\0');
    if (end != std::string::npos)
        text.resize(end);
    return text;
}

/// The CRS records found among the (E)VLRs.
struct CrsRecords {
    std::optional<std::vector<std::byte>> geoKeys;    // 34735
    std::optional<std::vector<std::byte>> geoDoubles; // 34736
    std::optional<std::vector<std::byte>> geoAscii;   // 34737
    std::optional<std::vector<std::byte>> wkt;        // 2112
    bool laszip = false;
};

void collectRecord(ByteSource& source, const std::string& userId, std::uint16_t recordId,
                   std::uint64_t dataOffset, std::uint64_t length, CrsRecords& records) {
    if (userId == "laszip encoded") {
        records.laszip = true;
        return;
    }
    if (userId != "LASF_Projection")
        return;
    std::optional<std::vector<std::byte>>* slot = nullptr;
    switch (recordId) {
    case 34735:
        slot = &records.geoKeys;
        break;
    case 34736:
        slot = &records.geoDoubles;
        break;
    case 34737:
        slot = &records.geoAscii;
        break;
    case 2112:
        slot = &records.wkt;
        break;
    default:
        return;
    }
    // CRS records are small; an EVLR may claim a 64-bit length, bounded by the file size
    // already, but no CRS needs more than a few MiB.
    constexpr std::uint64_t kMaxCrsRecord = std::uint64_t{16} << 20;
    if (length > kMaxCrsRecord)
        return;
    std::vector<std::byte> bytes(static_cast<std::size_t>(length));
    source.read(dataOffset, bytes);
    *slot = std::move(bytes);
}

struct ParsedHeader {
    LasHeader header;
    CrsRecords crs;
    std::uint64_t pointsEnd = 0;
};

ParsedHeader parseHeader(ByteSource& source, const std::string& name) {
    const std::uint64_t fileSize = source.size();
    if (fileSize < 4)
        invalid(name, "not a LAS file (" + std::to_string(fileSize) + " bytes, no LASF signature)");
    std::array<std::byte, kHeaderSize14> raw{};
    source.read(0, std::span(raw).first(4));
    if (std::memcmp(raw.data(), "LASF", 4) != 0)
        invalid(name, "not a LAS file (no LASF signature)");
    // LAZ first, whatever else is wrong: it is the likeliest reason for a failure. LASzip
    // marks compressed files by setting bit 7 of the point format (byte 104), and bit 6 as well
    // for the LAS 1.4 formats; what is left is a format of 0..10. Any other byte (99 = bit 6
    // and 35, say) is an unsupported format, reported below.
    const bool lazExtension = name.size() >= 4 && lowercase(name.substr(name.size() - 4)) == ".laz";
    std::array<std::byte, 1> formatProbe{};
    if (fileSize > 104)
        source.read(104, formatProbe);
    const unsigned probedFormat = std::to_integer<unsigned>(formatProbe[0]);
    const bool lazFormat = (probedFormat & 0x80u) != 0 && (probedFormat & 0x3Fu) <= 10;
    if (lazExtension || lazFormat)
        invalid(name, "LAZ is compressed; not supported (decompress it first, e.g. with "
                      "'pdal translate in.laz out.las' or 'laszip -i in.laz -o out.las')");
    if (fileSize < kHeaderSize12)
        invalid(name, "truncated: " + std::to_string(fileSize) +
                          " bytes, shorter than a LAS header (227 bytes)");
    source.read(0, std::span(raw).first(kHeaderSize12));
    const std::span<const std::byte> bytes(raw);

    ParsedHeader parsed;
    LasHeader& h = parsed.header;
    h.versionMajor = static_cast<int>(field<std::uint8_t>(bytes, 24));
    h.versionMinor = static_cast<int>(field<std::uint8_t>(bytes, 25));
    if (h.versionMajor != 1 || h.versionMinor > 4)
        invalid(name, "LAS version " + std::to_string(h.versionMajor) + "." +
                          std::to_string(h.versionMinor) + " is not supported (1.0 to 1.4 are)");
    h.globalEncoding = field<std::uint16_t>(bytes, 6);
    h.headerSize = field<std::uint16_t>(bytes, 94);
    h.pointDataOffset = field<std::uint32_t>(bytes, 96);
    h.vlrCount = field<std::uint32_t>(bytes, 100);
    const auto formatByte = field<std::uint8_t>(bytes, 104);
    h.recordLength = field<std::uint16_t>(bytes, 105);
    const std::uint64_t legacyCount = field<std::uint32_t>(bytes, 107);
    for (int i = 0; i < 3; ++i) {
        h.scale[static_cast<std::size_t>(i)] =
            field<double>(bytes, 131 + 8 * static_cast<std::size_t>(i));
        h.offset[static_cast<std::size_t>(i)] =
            field<double>(bytes, 155 + 8 * static_cast<std::size_t>(i));
    }
    // Header order: max x, min x, max y, min y, max z, min z.
    for (std::size_t axis = 0; axis < 3; ++axis) {
        h.bounds[axis + 3] = field<double>(bytes, 179 + 16 * axis);
        h.bounds[axis] = field<double>(bytes, 187 + 16 * axis);
    }

    h.pointFormat = formatByte;
    if (h.pointFormat > 10)
        invalid(name, "point data record format " + std::to_string(h.pointFormat) +
                          " is not supported (0 to 10 are)");

    const std::uint16_t minHeader = h.versionMinor >= 4   ? kHeaderSize14
                                    : h.versionMinor == 3 ? kHeaderSize13
                                                          : kHeaderSize12;
    if (h.headerSize < minHeader)
        invalid(name, "header size " + std::to_string(h.headerSize) + " is below the " +
                          std::to_string(minHeader) + " bytes of a LAS 1." +
                          std::to_string(h.versionMinor) + " header");
    if (h.headerSize > fileSize)
        invalid(name, "truncated: the header declares " + std::to_string(h.headerSize) +
                          " bytes but the file has " + std::to_string(fileSize));
    std::uint64_t evlrStart = 0;
    std::uint32_t evlrCount = 0;
    h.pointCount = legacyCount;
    if (h.versionMinor >= 4) {
        source.read(kHeaderSize12,
                    std::span(raw).subspan(kHeaderSize12, kHeaderSize14 - kHeaderSize12));
        evlrStart = field<std::uint64_t>(bytes, 235);
        evlrCount = field<std::uint32_t>(bytes, 243);
        const auto extendedCount = field<std::uint64_t>(bytes, 247);
        if (extendedCount != 0 && legacyCount != 0 && extendedCount != legacyCount)
            invalid(name, "the header's point counts disagree (legacy " +
                              std::to_string(legacyCount) + ", 64-bit " +
                              std::to_string(extendedCount) + ")");
        if (extendedCount != 0)
            h.pointCount = extendedCount;
    }

    for (std::size_t axis = 0; axis < 3; ++axis) {
        if (!std::isfinite(h.scale[axis]) || h.scale[axis] == 0.0 || !std::isfinite(h.offset[axis]))
            invalid(name, std::string("the ") + "xyz"[axis] +
                              " scale factor or offset is zero or "
                              "not finite");
    }
    if (h.recordLength < kMinRecordLength[static_cast<std::size_t>(h.pointFormat)])
        invalid(name,
                "point record length " + std::to_string(h.recordLength) + " is below the " +
                    std::to_string(kMinRecordLength[static_cast<std::size_t>(h.pointFormat)]) +
                    " bytes of point format " + std::to_string(h.pointFormat));
    if (h.pointDataOffset < h.headerSize)
        invalid(name, "the point data offset " + std::to_string(h.pointDataOffset) +
                          " lies inside the " + std::to_string(h.headerSize) + "-byte header");
    if (h.pointDataOffset > fileSize)
        invalid(name, "truncated: the point data should start at byte " +
                          std::to_string(h.pointDataOffset) + " but the file has " +
                          std::to_string(fileSize) + " bytes");
    const std::uint64_t available = fileSize - h.pointDataOffset;
    if (h.pointCount > available / h.recordLength)
        invalid(name, "truncated or lying header: it declares " + std::to_string(h.pointCount) +
                          " point records of " + std::to_string(h.recordLength) +
                          " bytes from byte " + std::to_string(h.pointDataOffset) +
                          ", but the file has room for " +
                          std::to_string(available / h.recordLength));
    parsed.pointsEnd = h.pointDataOffset + h.pointCount * h.recordLength;

    // VLRs: between the header and the point data, each within that space.
    std::uint64_t pos = h.headerSize;
    for (std::uint32_t i = 0; i < h.vlrCount; ++i) {
        if (pos + kVlrHeaderSize > h.pointDataOffset)
            invalid(name, "variable length record " + std::to_string(i + 1) + " of " +
                              std::to_string(h.vlrCount) + " runs into the point data");
        std::array<std::byte, kVlrHeaderSize> vlr{};
        source.read(pos, vlr);
        const std::string userId = trimmedText(std::span<const std::byte>(vlr).subspan(2, 16));
        const auto recordId = field<std::uint16_t>(vlr, 18);
        const std::uint64_t length = field<std::uint16_t>(vlr, 20);
        if (pos + kVlrHeaderSize + length > h.pointDataOffset)
            invalid(name, "variable length record " + std::to_string(i + 1) + " of " +
                              std::to_string(h.vlrCount) + " runs into the point data");
        collectRecord(source, userId, recordId, pos + kVlrHeaderSize, length, parsed.crs);
        pos += kVlrHeaderSize + length;
    }

    // EVLRs (1.4): after the point data, each within the file.
    if (evlrCount > 0) {
        if (evlrStart < parsed.pointsEnd || evlrStart > fileSize)
            invalid(name, "the extended variable length records start at byte " +
                              std::to_string(evlrStart) + ", outside the bytes after the points");
        pos = evlrStart;
        for (std::uint32_t i = 0; i < evlrCount; ++i) {
            if (kEvlrHeaderSize > fileSize - pos)
                invalid(name, "truncated: extended variable length record " +
                                  std::to_string(i + 1) + " of " + std::to_string(evlrCount) +
                                  " runs past the end of the file");
            std::array<std::byte, kEvlrHeaderSize> evlr{};
            source.read(pos, evlr);
            const std::string userId = trimmedText(std::span<const std::byte>(evlr).subspan(2, 16));
            const auto recordId = field<std::uint16_t>(evlr, 18);
            const auto length = field<std::uint64_t>(evlr, 20);
            if (length > fileSize - pos - kEvlrHeaderSize)
                invalid(name, "truncated: extended variable length record " +
                                  std::to_string(i + 1) + " of " + std::to_string(evlrCount) +
                                  " runs past the end of the file");
            collectRecord(source, userId, recordId, pos + kEvlrHeaderSize, length, parsed.crs);
            pos += kEvlrHeaderSize + length;
        }
    }
    if (parsed.crs.laszip)
        invalid(name, "LAZ is compressed; not supported (it carries a LASzip record)");
    return parsed;
}

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

PointCloud readPoints(ByteSource& source, const std::string& name, const LasReadOptions& options,
                      const ProgressCallback& progress) {
    std::bitset<256> keepClass;
    if (options.classes.empty()) {
        keepClass.set();
    } else {
        for (const int code : options.classes) {
            if (code < 0 || code > 255)
                throw InvalidInputError(std::string(kStage) + ": classification " +
                                        std::to_string(code) + " is outside 0..255");
            keepClass.set(static_cast<std::size_t>(code));
        }
    }

    const ParsedHeader parsed = parseHeader(source, name);
    const LasHeader& h = parsed.header;
    PointCloud cloud;
    cloud.path = name;
    cloud.kind = InputKind::Las;
    cloud.crsWkt = crsOf(parsed, name);
    cloud.recordsRead = h.pointCount;

    const bool extended = h.pointFormat >= 6;
    const std::size_t recordLength = h.recordLength;
    const std::size_t recordsPerBuffer = std::max<std::size_t>(1, kBufferBytes / recordLength);
    std::vector<std::byte> buffer(recordLength * static_cast<std::size_t>(std::min<std::uint64_t>(
                                                     recordsPerBuffer, h.pointCount)));
    // Bounded by the file size, already checked: 24 bytes per point for at most
    // fileSize / 20 records.
    cloud.points.reserve(static_cast<std::size_t>(h.pointCount));

    const double sx = h.scale[0], sy = h.scale[1], sz = h.scale[2];
    const double ox = h.offset[0], oy = h.offset[1], oz = h.offset[2];
    for (std::uint64_t first = 0; first < h.pointCount; first += recordsPerBuffer) {
        const auto records = static_cast<std::size_t>(
            std::min<std::uint64_t>(recordsPerBuffer, h.pointCount - first));
        const std::span<std::byte> chunk(buffer.data(), records * recordLength);
        source.read(h.pointDataOffset + first * recordLength, chunk);
        for (std::size_t r = 0; r < records; ++r) {
            const std::span<const std::byte> record(chunk.data() + r * recordLength, recordLength);
            const auto returnByte = field<std::uint8_t>(record, 14);
            const auto flagByte = field<std::uint8_t>(record, 15);
            unsigned returnNumber = 0;
            unsigned returnCount = 0;
            unsigned classification = 0;
            bool withheld = false;
            if (extended) {
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
            const bool returnKept =
                options.returns == LasReturns::All ||
                (options.returns == LasReturns::First && returnNumber <= 1) ||
                (options.returns == LasReturns::Last && returnNumber >= returnCount);
            if (withheld || !returnKept || !keepClass.test(classification)) {
                ++cloud.filteredOut;
                continue;
            }
            const auto x = field<std::int32_t>(record, 0);
            const auto y = field<std::int32_t>(record, 4);
            const auto z = field<std::int32_t>(record, 8);
            cloud.points.push_back({x * sx + ox, y * sy + oy, z * sz + oz});
        }
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
    FileSource source(path);
    return readPoints(source, path, options, progress);
}

PointCloud readLasPointsFromMemory(std::span<const std::byte> data, const std::string& name,
                                   const LasReadOptions& options,
                                   const ProgressCallback& progress) {
    MemorySource source(data);
    return readPoints(source, name, options, progress);
}

LasHeader readLasHeader(const std::string& path) {
    FileSource source(path);
    return parseHeader(source, path).header;
}

} // namespace terratin::io

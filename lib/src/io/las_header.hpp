#pragma once
/// @file
/// The LAS header and its variable length records, read from a ByteSource and checked against
/// its size before anything is read at an offset it declares (LAS 1.4 R15, 2.4-2.8): the
/// public header block is read at fixed byte offsets; 1.0-1.2 stop at byte 227, 1.3 adds the
/// waveform offset (to 235), 1.4 the EVLR start and count and the 64-bit point counts (to
/// 375). LAZ is refused here, by its signs (the extension, the point format's compression bits,
/// a LASzip VLR).

#include "terratin/io/las_reader.hpp"

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace terratin::io::detail {

inline constexpr std::string_view kLasStage = "LasReader";

/// Reads whole byte ranges that the caller has checked against size().
class ByteSource {
public:
    virtual ~ByteSource() = default;
    [[nodiscard]] virtual std::uint64_t size() const = 0;
    /// Fills `out` from `offset`. Precondition: offset + out.size() <= size().
    virtual void read(std::uint64_t offset, std::span<std::byte> out) = 0;
};

/// A LAS file held in memory (the fuzzer, tests).
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

/// A LAS file on disk; IoError (naming `path`) when it cannot be opened, sized or read.
class FileSource final : public ByteSource {
public:
    explicit FileSource(const std::string& path);
    [[nodiscard]] std::uint64_t size() const override { return m_size; }
    void read(std::uint64_t offset, std::span<std::byte> out) override;

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

/// `bytes` as text, up to the first NUL.
std::string trimmedText(std::span<const std::byte> bytes);

/// The CRS records found among the (E)VLRs.
struct CrsRecords {
    std::optional<std::vector<std::byte>> geoKeys;    // 34735
    std::optional<std::vector<std::byte>> geoDoubles; // 34736
    std::optional<std::vector<std::byte>> geoAscii;   // 34737
    std::optional<std::vector<std::byte>> wkt;        // 2112
    bool laszip = false;
};

/// The header as read and checked, the CRS records of its (E)VLRs, and the end of the point
/// records.
struct ParsedHeader {
    LasHeader header;
    CrsRecords crs;
    std::uint64_t pointsEnd = 0;
};

/// The header of `source`, checked against its size, and the CRS records of its (E)VLRs;
/// InvalidInputError naming `name` for what is no LAS file, is LAZ, or disagrees with the
/// file's size; IoError when reading fails.
ParsedHeader parseHeader(ByteSource& source, const std::string& name);

} // namespace terratin::io::detail

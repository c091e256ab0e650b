#pragma once
/// @file
/// Random access to the bytes of a LAS or LAZ file, on disk or in memory. Reads are
/// positional and const, so threads can read different chunks of one file at once.

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <span>
#include <string>

namespace terratin::io::detail {

/// Reads whole byte ranges that the caller has checked against size().
class ByteSource {
public:
    virtual ~ByteSource() = default;
    [[nodiscard]] virtual std::uint64_t size() const = 0;
    /// Fills `out` from `offset`. Precondition: offset + out.size() <= size().
    /// Throws IoError when the bytes cannot be read.
    virtual void read(std::uint64_t offset, std::span<std::byte> out) const = 0;
};

/// A file held in memory by the caller, who keeps it alive as long as the source (the
/// fuzzers, tests).
class MemorySource final : public ByteSource {
public:
    explicit MemorySource(std::span<const std::byte> data) : m_data(data) {}
    [[nodiscard]] std::uint64_t size() const override { return m_data.size(); }
    void read(std::uint64_t offset, std::span<std::byte> out) const override {
        if (!out.empty())
            std::memcpy(out.data(), m_data.data() + offset, out.size());
    }

private:
    std::span<const std::byte> m_data;
};

/// A file on disk, read with POSIX pread (no shared file position). IoError naming `path`
/// (and `stage`, the reader that opened it) when it cannot be opened, sized or read.
class FileSource final : public ByteSource {
public:
    FileSource(const std::string& path, std::string_view stage);
    ~FileSource() override;
    FileSource(const FileSource&) = delete;
    FileSource& operator=(const FileSource&) = delete;

    [[nodiscard]] std::uint64_t size() const override { return m_size; }
    void read(std::uint64_t offset, std::span<std::byte> out) const override;

private:
    std::string m_path;
    std::string m_stage;
    int m_descriptor = -1;
    std::uint64_t m_size = 0;
};

} // namespace terratin::io::detail

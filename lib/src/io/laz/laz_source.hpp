#pragma once
/// @file
/// Random access to the bytes of a LAZ file, on disk or in memory. Reads are positional and
/// const, so threads can read different chunks of one file at the same time.

#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <string>

namespace terratin::io::laz {

class LazSource {
public:
    virtual ~LazSource() = default;
    [[nodiscard]] virtual std::uint64_t size() const = 0;
    /// Fills `out` from byte `offset`. Precondition: offset + out.size() <= size().
    /// Throws IoError when the file cannot be read.
    virtual void read(std::uint64_t offset, std::span<std::byte> out) const = 0;
};

/// The file at `path`; throws IoError when it cannot be opened.
[[nodiscard]] std::unique_ptr<LazSource> openFileSource(const std::string& path);
/// Bytes held by the caller, who keeps them alive as long as the source.
[[nodiscard]] std::unique_ptr<LazSource> memorySource(std::span<const std::byte> bytes);

} // namespace terratin::io::laz

#pragma once
/// @file
/// The header and VLR bytes of a repeated LAZ file and of its uncompressed LAS twin, made by
/// patching the input's own bytes at the fixed offsets of the LAS header (LAS 1.4 R15, 2.4):
/// the point counts multiplied, the offsets of what follows the points moved, and for the
/// twin the LASzip VLR taken out. Everything else (bounds, scales, CRS records, whatever a
/// writer put between the VLRs and the points) stays byte for byte as the input has it.

#include "laz_file.hpp"

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace terratin::lazrepeat {

/// How the tool's own errors start.
inline constexpr std::string_view kStage = "terratin-lazrepeat";

/// InvalidInputError "terratin-lazrepeat: '<file>': <what>".
[[noreturn]] void throwInvalid(std::string_view fileName, const std::string& what);

/// Where one VLR lies among the bytes before the point data: its 54-byte header and payload.
struct VlrPlace {
    std::size_t offset = 0;
    std::size_t size = 0;
};

/// The bytes after the chunk table whose offsets the header holds: the EVLRs of LAS 1.4, or
/// the waveform data record of LAS 1.3 stored inside the file. Empty (start == end) if none.
struct TailRange {
    std::uint64_t start = 0;
    std::uint64_t end = 0;
    [[nodiscard]] bool empty() const { return start == end; }
};

/// The LASzip VLR among the VLRs of `prefix`, the file's bytes before its point data.
/// InvalidInputError naming `fileName` when it is not there, or when the file is a COPC file
/// (its hierarchy EVLR addresses the input's chunks, so a repeated copy would lie).
[[nodiscard]] VlrPlace findLaszipVlr(std::span<const std::byte> prefix, const io::LasHeader& header,
                                     std::string_view fileName);

/// Multiplies by `copies` every point count of the header at the start of `prefix`: the
/// legacy 32-bit total and per-return counts (kept at 0 where the input left them 0, and set
/// to 0 in LAS 1.4 when the total no longer fits them) and LAS 1.4's 64-bit ones.
/// InvalidInputError when a count does not fit: LAS before 1.4 holds at most 2^32 - 1 points.
void scalePointCounts(std::span<std::byte> prefix, const io::LasHeader& header,
                      std::uint32_t copies, std::string_view fileName);

/// The input's tail (see TailRange), walked EVLR header by EVLR header and checked against
/// the file; InvalidInputError when it overlaps the chunks or runs past the end of the file.
[[nodiscard]] TailRange locateTail(const io::laz::LazFile& file, std::span<const std::byte> prefix);

/// Moves the header's offsets into the tail (the EVLR start of LAS 1.4, the waveform record
/// start of LAS 1.3 and 1.4 when it points into the tail) from `tail` to `newStart`.
void moveTailOffsets(std::span<std::byte> prefix, const io::LasHeader& header,
                     const TailRange& tail, std::uint64_t newStart);

/// Sets the chunk size of the LASzip VLR at `laszip` to variable (0xFFFFFFFF): the chunk
/// table then lists each chunk's point count, so chunks of any sizes may follow each other.
void markVariableChunks(std::span<std::byte> prefix, const VlrPlace& laszip);

/// The bytes before the point data of the uncompressed twin: `prefix` without the LASzip VLR,
/// the compression bits (7 and 6) cleared from the point format, the VLR count and the
/// offset to the point data lowered to match.
[[nodiscard]] std::vector<std::byte> uncompressedPrefix(std::span<const std::byte> prefix,
                                                        const VlrPlace& laszip);

} // namespace terratin::lazrepeat

#pragma once
/// @file
/// What the LAS and LAZ fuzzers share: the filters an input picks with its last byte, so that
/// the class and return paths are exercised on every record layout, and the reading itself,
/// with the postcondition every accepted file must meet.

#include "terratin/error.hpp"
#include "terratin/io/las_reader.hpp"

#include <cstddef>
#include <span>
#include <string>

namespace terratin::fuzz {

/// The filters `input` picks with its last byte: bit 0 set keeps only classes 2 and
/// byte >> 1; bits 1-2 keep the first returns (2), the last (4) or all (0, 6). An empty input
/// keeps everything. The thread count is left at its default.
[[nodiscard]] inline io::LasReadOptions filtersFromLastByte(std::span<const std::byte> input) {
    io::LasReadOptions options;
    if (input.empty())
        return options;
    const auto selector = std::to_integer<unsigned>(input.back());
    if ((selector & 1u) != 0)
        options.classes = {2, static_cast<int>(selector >> 1)};
    options.returns = (selector & 6u) == 2u   ? io::LasReturns::First
                      : (selector & 6u) == 4u ? io::LasReturns::Last
                                              : io::LasReturns::All;
    return options;
}

/// Reads `input` as the file `name` held in memory. terratin::Error is the reader's answer to
/// bad input and is swallowed; an accepted file that does not account for every record it
/// read (kept or filtered out) traps, which the fuzzer reports as a finding, as it does any
/// crash, sanitizer report, other exception or hang.
inline void readAndCheck(std::span<const std::byte> input, const std::string& name,
                         const io::LasReadOptions& options) {
    try {
        const io::PointCloud cloud = io::readLasPointsFromMemory(input, name, options);
        if (cloud.points.size() + cloud.filteredOut != cloud.recordsRead)
            __builtin_trap();
    } catch (const Error&) {
    }
}

} // namespace terratin::fuzz

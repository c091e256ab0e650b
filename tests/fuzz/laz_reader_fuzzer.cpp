// libFuzzer entry point for the LAZ reader (through LasReader, which hands compressed files on
// to it): any bytes as a LAZ file held in memory, decoded on two threads so that the chunks'
// parallel path is fuzzed too. The reader may throw terratin::Error (its contract for bad
// input); anything else - a crash, a sanitizer report, another exception type, a hang - is a
// finding.
//
// The last byte of the input also picks the filters, as in the LAS fuzzer.

#include "terratin/error.hpp"
#include "terratin/io/las_reader.hpp"

#include <cstddef>
#include <cstdint>
#include <span>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::span<const std::byte> bytes(reinterpret_cast<const std::byte*>(data), size);
    terratin::io::LasReadOptions options;
    options.threads = 2;
    if (size > 0) {
        const unsigned selector = data[size - 1];
        if ((selector & 1u) != 0)
            options.classes = {2, static_cast<int>(selector >> 1)};
        options.returns = (selector & 6u) == 2u   ? terratin::io::LasReturns::First
                          : (selector & 6u) == 4u ? terratin::io::LasReturns::Last
                                                  : terratin::io::LasReturns::All;
    }
    try {
        const terratin::io::PointCloud cloud =
            terratin::io::readLasPointsFromMemory(bytes, "fuzz.laz", options);
        // Postconditions that hold for any accepted file.
        if (cloud.points.size() + cloud.filteredOut != cloud.recordsRead)
            __builtin_trap();
    } catch (const terratin::Error&) {
    }
    return 0;
}

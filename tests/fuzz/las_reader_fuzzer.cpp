// libFuzzer entry point for LasReader: any bytes as a LAS file held in memory. The reader may
// throw terratin::Error (that is its contract for bad input); anything else - a crash, a
// sanitizer report, another exception type - is a finding.
//
// The first byte of the input also picks the filters, so that the class and return paths are
// exercised on every record layout.

#include "terratin/error.hpp"
#include "terratin/io/las_reader.hpp"

#include <cstddef>
#include <cstdint>
#include <span>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::span<const std::byte> bytes(reinterpret_cast<const std::byte*>(data), size);
    terratin::io::LasReadOptions options;
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
            terratin::io::readLasPointsFromMemory(bytes, "fuzz.las", options);
        // Postconditions that hold for any accepted file.
        if (cloud.points.size() + cloud.filteredOut != cloud.recordsRead)
            __builtin_trap();
    } catch (const terratin::Error&) {
    }
    return 0;
}

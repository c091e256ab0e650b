// libFuzzer entry point for LasReader: any bytes as a LAS file held in memory. The reader may
// throw terratin::Error (that is its contract for bad input); anything else - a crash, a
// sanitizer report, another exception type - is a finding.
//
// The last byte of the input also picks the filters (las_fuzz_input.hpp), so that the class
// and return paths are exercised on every record layout.

#include "las_fuzz_input.hpp"

#include <cstddef>
#include <cstdint>
#include <span>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::span<const std::byte> bytes(reinterpret_cast<const std::byte*>(data), size);
    terratin::fuzz::readAndCheck(bytes, "fuzz.las", terratin::fuzz::filtersFromLastByte(bytes));
    return 0;
}

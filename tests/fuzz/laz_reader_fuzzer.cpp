// libFuzzer entry point for the LAZ reader (through LasReader, which hands compressed files on
// to it): any bytes as a LAZ file held in memory, decoded on two threads so that the chunks'
// parallel path is fuzzed too. The reader may throw terratin::Error (its contract for bad
// input); anything else - a crash, a sanitizer report, another exception type, a hang - is a
// finding.
//
// The last byte of the input also picks the filters, as in the LAS fuzzer (las_fuzz_input.hpp).

#include "las_fuzz_input.hpp"

#include <cstddef>
#include <cstdint>
#include <span>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::span<const std::byte> bytes(reinterpret_cast<const std::byte*>(data), size);
    terratin::io::LasReadOptions options = terratin::fuzz::filtersFromLastByte(bytes);
    options.threads = 2;
    terratin::fuzz::readAndCheck(bytes, "fuzz.laz", options);
    return 0;
}

// libFuzzer entry point for TextReader: any bytes as a delimited text file held in memory.
// terratin::Error is the reader's answer to bad input; anything else is a finding. The last
// byte picks the columns and delimiter options, so that header lookup and every splitter run.

#include "terratin/error.hpp"
#include "terratin/io/text_reader.hpp"

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string_view>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string_view text(reinterpret_cast<const char*>(data), size);
    terratin::io::TextReadOptions options;
    if (size > 0) {
        const unsigned selector = data[size - 1];
        switch (selector % 4) {
        case 1:
            options.columns = {"2", "1", "3"};
            break;
        case 2:
            options.columns = {"x", "y", "z"};
            break;
        case 3:
            options.columns = {"3", "y", "17"};
            break;
        default:
            break;
        }
        constexpr char kDelimiters[] = {' ', ',', ';', '|', '\t'};
        if ((selector & 4u) != 0)
            options.delimiter = kDelimiters[(selector >> 3) % 5];
    }
    try {
        const terratin::io::PointCloud cloud =
            terratin::io::readTextPointsFromMemory(text, "fuzz.xyz", options);
        // Postconditions: one point per data line, every coordinate finite.
        if (cloud.points.size() != cloud.recordsRead || cloud.points.empty())
            __builtin_trap();
        for (const terratin::Point3& p : cloud.points)
            if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
                __builtin_trap();
    } catch (const terratin::Error&) {
    }
    return 0;
}

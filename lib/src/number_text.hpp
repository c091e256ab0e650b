#pragma once
/// @file
/// Numbers in the library's messages: the value the user gave, in its shortest exact form.

#include <charconv>
#include <cmath>
#include <string>

namespace terratin::detail {

/// `value` as the shortest decimal text that reads back as the same double (std::to_chars):
/// "5000000.25", "1e+300", "5e-324", "-0"; "nan", "inf" and "-inf" for the others. Unlike
/// std::to_string (printf's %f), it neither writes 300 digits for 1e300 nor rounds 5e-324 to
/// "0.000000".
inline std::string numberText(double value) {
    if (std::isnan(value))
        return "nan";
    char text[32];
    const std::to_chars_result end = std::to_chars(text, text + sizeof text, value);
    return std::string(text, end.ptr);
}

} // namespace terratin::detail

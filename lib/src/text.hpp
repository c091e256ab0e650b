#pragma once
/// @file
/// Small text helpers of the library (the tools and the Python module have their own).

#include <algorithm>
#include <cctype>
#include <string>
#include <string_view>

namespace terratin::detail {

/// `text` with every character lowered by std::tolower (ASCII letters in the "C" locale the
/// library runs in): names of methods, formats and extensions compare case-insensitively.
inline std::string lowercase(std::string_view text) {
    std::string lower(text);
    std::transform(lower.begin(), lower.end(), lower.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return lower;
}

} // namespace terratin::detail

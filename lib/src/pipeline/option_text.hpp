#pragma once
/// @file
/// The text of a build option's value read as what it holds: numbers, counts, byte sizes,
/// flags, choices, lists, CRSs. `name` is the option as messages name it (markOption); each
/// refusal is an InvalidInputError naming it. Private to the option table.

#include "../text.hpp"
#include "terratin/error.hpp"

#include <charconv>
#include <cstdint>
#include <initializer_list>
#include <string>
#include <string_view>
#include <system_error>
#include <utility>
#include <vector>

namespace terratin::detail {

[[noreturn]] void refuse(const std::string& message);
/// The message Boost.Program_options gave for a number it could not read, kept for both
/// spellings.
[[noreturn]] void refuseNumberText(const std::string& text, const std::string& name);

// std::from_chars over the whole text; a leading '+' is accepted, as the command line always did.
template <class Number> bool readWhole(std::string_view text, Number& number) {
    if (text.size() > 1 && text.front() == '+' && text[1] != '-')
        text.remove_prefix(1);
    const char* end = text.data() + text.size();
    const auto [ptr, error] = std::from_chars(text.data(), end, number);
    return !text.empty() && error == std::errc() && ptr == end;
}

// Digits only: "-1" is refused, never wrapped to 2^64 - 1. Ranges are checkBuildOptions'.
template <class Count> Count parseCount(const std::string& text, const std::string& name) {
    Count count{};
    const char* end = text.data() + text.size();
    const auto [ptr, error] = std::from_chars(text.data(), end, count);
    if (error == std::errc::result_out_of_range)
        refuse(name + " is too large (got '" + text + "')");
    if (text.empty() || error != std::errc() || ptr != end)
        refuse(name + " takes a whole number without sign (got '" + text + "')");
    return count;
}

double parseNumber(const std::string& text, const std::string& name);
/// "2G", "512M", "1.5GiB", "1000000": a number of bytes with K, M, G or T, powers of 1024.
std::uint64_t parseByteSize(const std::string& text, const std::string& name);
/// true or false, case-insensitively.
bool parseFlag(const std::string& text, const std::string& name);
/// "a, b or c".
std::string alternatives(const std::vector<std::string_view>& names);

// One of `choices` by name, case-insensitively.
template <class Value>
Value parseChoice(const std::string& text, const std::string& name,
                  std::initializer_list<std::pair<std::string_view, Value>> choices) {
    const std::string key = detail::lowercase(text);
    std::vector<std::string_view> names;
    for (const auto& [choiceName, value] : choices) {
        if (key == choiceName)
            return value;
        names.push_back(choiceName);
    }
    refuse(name + " must be " + alternatives(names) + " (got '" + text + "')");
}

/// The items of a comma-separated list; a trailing comma ends with an empty item.
std::vector<std::string> splitList(const std::string& text);
/// A CRS given as an empty (or blank) string would mean "no CRS" to the library, which is not
/// what a caller naming the option asks for.
std::string parseCrs(const std::string& text, const std::string& name);

} // namespace terratin::detail

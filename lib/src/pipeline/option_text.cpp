#include "option_text.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace terratin::detail {

[[noreturn]] void refuse(const std::string& message) {
    throw InvalidInputError(message);
}

// The message Boost.Program_options gave for a number it could not read, kept for both spellings.
[[noreturn]] void refuseNumberText(const std::string& text, const std::string& name) {
    refuse("the argument ('" + text + "') for option '" + name + "' is invalid");
}

double parseNumber(const std::string& text, const std::string& name) {
    double number = 0.0;
    if (!readWhole(text, number))
        refuseNumberText(text, name);
    return number;
}

// "2G", "512M", "1.5GiB", "1000000": a number of bytes with K, M, G or T, powers of 1024.
std::uint64_t parseByteSize(const std::string& text, const std::string& name) {
    const auto refuseSize = [&] {
        refuse(name + " takes a size such as 2G or 512M (got '" + text + "')");
    };
    const std::size_t unitAt = std::min(text.find_first_not_of("0123456789.+eE"), text.size());
    std::string unit = lowercase(text.substr(unitAt));
    if (unit.size() > 1 && unit.back() == 'b')
        unit.pop_back(); // "GB", "GiB"
    if (unit.size() == 2 && unit.back() == 'i')
        unit.pop_back();
    double power = 0.0;
    if (!unit.empty()) {
        const std::size_t at = std::string_view("kmgt").find(unit);
        if (unit.size() != 1 || at == std::string_view::npos)
            refuseSize();
        power = static_cast<double>(at + 1);
    }
    double number = 0.0;
    if (!readWhole(std::string_view(text).substr(0, unitAt), number))
        refuseSize();
    const double bytes = number * std::pow(1024.0, power);
    if (!(bytes >= 1.0) || bytes > 0x1p62)
        refuseSize();
    return static_cast<std::uint64_t>(bytes);
}

bool parseFlag(const std::string& text, const std::string& name) {
    const std::string key = lowercase(text);
    if (key == "true")
        return true;
    if (key == "false")
        return false;
    refuse(name + " takes true or false (got '" + text + "')");
}

// "a, b or c".
std::string alternatives(const std::vector<std::string_view>& names) {
    std::string list;
    for (std::size_t i = 0; i < names.size(); ++i)
        list += std::string(i == 0                  ? ""
                            : i + 1 == names.size() ? " or "
                                                    : ", ") +
                std::string(names[i]);
    return list;
}

std::vector<std::string> splitList(const std::string& text) {
    std::vector<std::string> items;
    std::string item;
    std::istringstream stream(text);
    while (std::getline(stream, item, ','))
        items.push_back(item);
    if (!text.empty() && text.back() == ',')
        items.emplace_back();
    return items;
}

// A CRS given as an empty (or blank) string would mean "no CRS" to the library, which is not
// what a caller naming the option asks for.
std::string parseCrs(const std::string& text, const std::string& name) {
    if (text.find_first_not_of(" \t\r\n") == std::string::npos)
        refuse(name + " needs a CRS (EPSG:n, WKT, PROJ string, .prj file), not an empty string");
    return text;
}

} // namespace terratin::detail

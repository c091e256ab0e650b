// Finding a build option by its name, "did you mean", naming options the caller's way, and
// parsing a caller's options into BuildOptions.

#include "terratin/pipeline/build_option_table.hpp"

#include "option_text.hpp"
#include "terratin/error.hpp"
#include "terratin/io/tin_format.hpp"

#include <algorithm>

namespace terratin {

namespace {

using terratin::detail::refuse;

// Edits (insertions, deletions, substitutions) that turn `a` into `b`.
std::size_t editDistance(std::string_view a, std::string_view b) {
    std::vector<std::size_t> row(b.size() + 1);
    for (std::size_t j = 0; j <= b.size(); ++j)
        row[j] = j;
    for (std::size_t i = 1; i <= a.size(); ++i) {
        std::size_t diagonal = row[0];
        row[0] = i;
        for (std::size_t j = 1; j <= b.size(); ++j) {
            const std::size_t above = row[j];
            row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] != b[j - 1])});
            diagonal = above;
        }
    }
    return row[b.size()];
}

// A name two edits or fewer from `name`, for "did you mean"; empty when none is that close.
std::string closestName(std::string_view name, OptionSpelling spelling) {
    constexpr std::size_t kMaxTypoEdits = 2; // one slip of the finger, or two
    std::string closest;
    std::size_t best = kMaxTypoEdits + 1;
    for (const BuildOptionSpec& option : buildOptionTable()) {
        const std::string candidate = optionName(option, spelling);
        const std::size_t distance = editDistance(name, candidate);
        if (distance < best) {
            best = distance;
            closest = candidate;
        }
    }
    return closest;
}

[[noreturn]] void refuseUnknown(std::string_view name, OptionSpelling spelling) {
    const std::string closest = closestName(name, spelling);
    refuse("unknown option '" + std::string(name) + "'" +
           (closest.empty() ? std::string() : "; did you mean '" + closest + "'?"));
}

} // namespace

std::string closestBuildOption(std::string_view name, OptionSpelling spelling) {
    return closestName(name, spelling);
}

namespace {

bool given(const std::vector<OptionValue>& values, std::string_view keyword,
           OptionSpelling spelling) {
    return std::any_of(values.begin(), values.end(), [&](const OptionValue& value) {
        const BuildOptionSpec* option = findBuildOption(value.name, spelling);
        return option != nullptr && option->keyword == keyword;
    });
}

} // namespace

const BuildOptionSpec* findBuildOption(std::string_view name, OptionSpelling spelling) {
    if (spelling == OptionSpelling::CommandLine && name.substr(0, 2) == "--")
        name.remove_prefix(2);
    for (const BuildOptionSpec& option : buildOptionTable())
        if (name == (spelling == OptionSpelling::Keyword ? option.keyword : option.longFlag))
            return &option;
    return nullptr;
}

std::string optionName(const BuildOptionSpec& option, OptionSpelling spelling) {
    if (spelling == OptionSpelling::Keyword)
        return std::string(option.keyword);
    return option.positional ? std::string(option.valueName) : "--" + std::string(option.longFlag);
}

std::string optionName(std::string_view keyword, OptionSpelling spelling) {
    const BuildOptionSpec* option = findBuildOption(keyword, OptionSpelling::Keyword);
    if (option == nullptr)
        throw Error("optionName: no build option has the keyword '" + std::string(keyword) + "'");
    return optionName(*option, spelling);
}

OptionNaming optionNaming(OptionSpelling spelling) {
    return [spelling](std::string_view keyword) { return optionName(keyword, spelling); };
}

namespace {

// applyBuildOption, its messages naming options by keyword (markOption).
void applyNamingByKeyword(BuildOptions& options, const OptionValue& value,
                          OptionSpelling spelling) {
    const BuildOptionSpec* option = findBuildOption(value.name, spelling);
    if (option == nullptr)
        refuseUnknown(value.name, spelling);
    // A C string ends at a NUL: a path holding one would name another file.
    if (value.text.find('\0') != std::string::npos)
        refuse(markOption(option->keyword) + " holds a NUL character");
    option->apply(options, value.text, markOption(option->keyword));
}

BuildOptions parseNamingByKeyword(const std::vector<OptionValue>& values, OptionSpelling spelling) {
    const auto name = [](std::string_view keyword) { return markOption(keyword); };
    // What is missing first: a usage line is more use than a complaint about one value.
    if (!given(values, "inputs", spelling))
        refuse("missing " + name("inputs"));
    const bool tiles = given(values, "tiles_dir", spelling);
    if (!given(values, "output", spelling) && !tiles)
        refuse(spelling == OptionSpelling::CommandLine ? std::string("missing -o OUTPUT")
                                                       : "missing " + name("output"));
    if (given(values, "output", spelling) && tiles)
        refuse(name("tiles_dir") + " takes the place of " + name("output") + ": give one");
    BuildOptions options;
    options.optionSpelling = spelling;
    for (const OptionValue& value : values)
        applyNamingByKeyword(options, value, spelling);
    if (options.refine && options.refine->fillHoles && given(values, "max_hole", spelling))
        refuse(name("max_hole") + " and " + name("fill_holes") +
               " contradict each other: give one");
    if (!options.format)
        options.format = tiles ? io::TinFormat::GeoPackage : io::tinFormatFromPath(options.output);
    checkBuildOptions(options);
    return options;
}

} // namespace

void applyBuildOption(BuildOptions& options, const OptionValue& value, OptionSpelling spelling) {
    try {
        applyNamingByKeyword(options, value, spelling);
    } catch (Error& error) {
        error.nameOptions(optionNaming(spelling));
        throw;
    }
}

BuildOptions parseBuildOptions(const std::vector<OptionValue>& values, OptionSpelling spelling) {
    try {
        return parseNamingByKeyword(values, spelling);
    } catch (Error& error) {
        error.nameOptions(optionNaming(spelling));
        throw;
    }
}

} // namespace terratin

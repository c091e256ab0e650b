#pragma once
/// @file
/// Every option of a build, parsed from text the same way for every caller (the GDAL way:
/// `gdalwarp_bin.cpp` maps argv onto `gdalwarp_lib.cpp`). The `terratin` command line builds its
/// Boost.Program_options description from buildOptionTable() and hands what the user typed to
/// parseBuildOptions with OptionSpelling::CommandLine; a binding (Python) hands its keyword
/// arguments to the same function with OptionSpelling::Keyword, so both get the same checks and
/// the same messages, each naming the option its caller's way.
///
/// A keyword binding turns each argument into text: a bool into "true" / "false" (Flag); a
/// number into its decimal text; a list into one OptionValue per item for the Repeatable
/// options (`inputs`, `classes`) and into one comma-joined text for the List option
/// (`columns`); anything else into its text.

#include "terratin/error.hpp"
#include "terratin/pipeline/build_pipeline.hpp"
#include "terratin/pipeline/option_spelling.hpp"

#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace terratin {

/// What an option's text holds.
enum class OptionKind {
    /// "true" or "false" (any case); the command line gives "true" when the flag is present.
    Flag,
    /// A finite or non-finite real number ("2.5", "1e3"); each option states its range.
    Number,
    /// A whole number ("0", "1024"). The counts refuse a sign rather than wrap it; `band`
    /// takes one, to say that a band below 1 does not exist.
    Count,
    /// Any text, or one of the names its help lists.
    Text,
    /// Items separated by commas ("1,2,3"), given once.
    List,
    /// Given any number of times; every value adds to the option (a comma list each, for
    /// `classes`).
    Repeatable,
};

/// One option of a build.
struct BuildOptionSpec {
    /// snake_case, the keyword of a library or Python caller: "max_error", "t_srs".
    std::string_view keyword;
    /// The long command-line name without its dashes ("max-error", "t_srs"); for the inputs, the
    /// name of the positional arguments ("input").
    std::string_view longFlag;
    /// The one-letter command-line name ('o' for -o), 0 when there is none.
    char shortFlag = 0;
    OptionKind kind = OptionKind::Text;
    /// The command line takes it without a dash, as its positional arguments (the inputs).
    bool positional = false;
    /// What the help writes for the value ("E", "METHOD"); empty for a Flag.
    std::string_view valueName;
    /// The value BuildOptions holds when the option is not given, as the help shows it ("1",
    /// "auto"); empty when there is none to show. Parsing it gives BuildOptions' default.
    std::string_view defaultText;
    /// One sentence or two for --help.
    std::string help;
    /// Parses `text` into `options`; `name` is the option marked for messages (markOption).
    /// Throws InvalidInputError when the text is not a value of the option.
    void (*apply)(BuildOptions& options, const std::string& text,
                  const std::string& name) = nullptr;
};

/// One option given by a caller, by its name (keyword or command-line, see OptionSpelling) and
/// its text.
struct OptionValue {
    std::string name;
    std::string text;
};

/// Every build option, in the order of `terratin build --help`. Built once; the help of the
/// bounded options states the library's limits (kMaxThreads, kMaxRefineCells...).
std::span<const BuildOptionSpec> buildOptionTable();

/// The heading of the triangulation methods' tuning options in `terratin build --help`.
inline constexpr std::string_view kMethodTuningHeading =
    "Triangulation methods (their defaults suit every input)";

/// The heading `option` stands under in `terratin build --help`: kMethodTuningHeading for the
/// insertion order and the methods' settings (seed, order, method, locate, searchers,
/// queue_length, searchers_help), empty (the build's own options) for every other.
std::string_view buildOptionHeading(const BuildOptionSpec& option);

/// The option named `name` the `spelling` way: a keyword ("max_error") or a long command-line
/// name with or without its dashes ("--max-error", "max-error"). Null when there is none.
const BuildOptionSpec* findBuildOption(std::string_view name, OptionSpelling spelling);

/// The option name two edits or fewer from `name` (the closest), spelled the `spelling` way,
/// for "did you mean"; empty when none is that close.
std::string closestBuildOption(std::string_view name, OptionSpelling spelling);

/// How messages name `option`: "--max-error" / "max_error"; the inputs "INPUT" / "inputs".
std::string optionName(const BuildOptionSpec& option, OptionSpelling spelling);

/// optionName of the option whose keyword is `keyword` (which must exist).
std::string optionName(std::string_view keyword, OptionSpelling spelling);

/// optionName(keyword, spelling) as an OptionNaming, for Error::nameOptions: the modules below
/// this table name an option by its keyword (markOption), and the messages reach the caller
/// naming it the `spelling` way.
OptionNaming optionNaming(OptionSpelling spelling);

/// Parses `value` into `options`, as if it came after the ones parsed before: a Repeatable option
/// adds to what is there, any other replaces it; the simplification options (max_error,
/// max_points, max_triangles, max_hole, fill_holes=true) switch `options.refine` on. Throws
/// InvalidInputError naming the option the `spelling` way when the name is unknown ("unknown
/// option 'max_eror'; did you mean 'max_error'?") or the text is not a value of the option
/// ("--method must be sequential, batch, circumcircle, strips or auto (got 'fast')").
void applyBuildOption(BuildOptions& options, const OptionValue& value, OptionSpelling spelling);

/// The BuildOptions that `values` ask for, in order, from BuildOptions' defaults: every value
/// applied (applyBuildOption), then checked as a whole. Throws InvalidInputError, naming options
/// the `spelling` way: no inputs, no output (both checked first), a value refused by
/// applyBuildOption, keep_geographic with t_srs, an output format that is neither given nor
/// known from the output's extension, or anything checkBuildOptions refuses. The result's
/// optionSpelling is `spelling`, so that runBuild's messages name options the same way.
BuildOptions parseBuildOptions(const std::vector<OptionValue>& values, OptionSpelling spelling);

} // namespace terratin

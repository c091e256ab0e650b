#include "cli_options.hpp"

#include "terratin/error.hpp"
#include "terratin/io/tin_format.hpp"
#include "terratin/pipeline/build_option_table.hpp"

#include <boost/program_options.hpp>

#include <cctype>
#include <sstream>
#include <string>
#include <vector>

namespace terratin::cli {

namespace po = boost::program_options;

namespace {

constexpr const char* kUsage = "Usage: terratin build INPUT... -o OUTPUT [options]\n"
                               "       terratin --help | --version | --formats\n";

constexpr const char* kDescription =
    "Builds an exactly Delaunay TIN from a DEM raster (any format GDAL reads: GeoTIFF, VRT,\n"
    "DTED, HGT, ASCII grid...). Every valid cell centre becomes a vertex with the cell's\n"
    "elevation; nodata, masked and NaN cells are skipped. The output holds one Polygon Z\n"
    "triangle per feature with z1 z2 z3 z_min z_max z_mean slope_deg slope_pct aspect_deg\n"
    "area_2d area_3d nx ny nz (GeoPackage, Shapefile, FlatGeobuf), in the input's CRS, or\n"
    "the mesh itself (2DM, PLY, OBJ, LandXML).\n\n"
    "Point clouds too: LAS 1.0-1.4 (.las) and LAZ (.laz, COPC too), delimited text (.xyz\n"
    ".txt .csv...: x y z per line, separated by spaces, ',', ';' or '|', optional header\n"
    "line) and any OGR point layer (GeoPackage, Shapefile, GeoJSON...). Several inputs are\n"
    "merged after being brought into one CRS. Geographic input is projected to the UTM/UPS\n"
    "zone of its centre unless --t_srs or --keep-geographic says otherwise; elevations are\n"
    "never converted except by --z-factor.\n\n"
    "With --max-error, --max-points or --max-triangles the DEM is simplified instead: greedy\n"
    "insertion of the cell farthest from the TIN, kept exactly Delaunay, until the tolerance\n"
    "or a limit is reached; nodata regions larger than --max-hole cells become holes.\n\n"
    "Exit status: 0 success, 1 error (one line on stderr), 2 bad command line.\n";

// How Boost.Program_options reads a valued option of the library's table: as text, which the
// library parses (a count read by Boost as unsigned would wrap "-1"). Boost owns the result.
po::value_semantic* textValue(const BuildOptionSpec& option) {
    const std::string valueName(option.valueName);
    if (option.kind == OptionKind::Repeatable)
        return po::value<std::vector<std::string>>()->composing()->value_name(valueName);
    po::typed_value<std::string>* value = po::value<std::string>()->value_name(valueName);
    if (!option.defaultText.empty())
        value->default_value(std::string(option.defaultText)); // shown by --help only
    return value;
}

// The table's options under `heading` (buildOptionHeading), in the table's order.
void addTableOptions(po::options_description& options, std::string_view heading) {
    for (const BuildOptionSpec& option : buildOptionTable()) {
        if (option.positional || buildOptionHeading(option) != heading)
            continue;
        std::string name(option.longFlag);
        if (option.shortFlag != 0)
            name += std::string(",") + option.shortFlag;
        if (option.kind == OptionKind::Flag)
            options.add_options()(name.c_str(), option.help.c_str());
        else
            options.add_options()(name.c_str(), textValue(option), option.help.c_str());
    }
}

po::options_description buildOptionsDescription() {
    po::options_description build("Options of 'terratin build'");
    addTableOptions(build, {});
    // clang-format off
    build.add_options()
        ("quiet,q", "no progress and no summary")
        ("json", "print a JSON report on stdout (counts, CRS, seconds per phase)")
        ("help,h", "show this help");
    // clang-format on
    po::options_description tuning{std::string(kMethodTuningHeading)};
    addTableOptions(tuning, kMethodTuningHeading);
    po::options_description options;
    options.add(build).add(tuning);
    return options;
}

// What the user typed for the library's options, in command-line order; a flag as "true".
std::vector<OptionValue> tableValues(const po::parsed_options& parsed) {
    std::vector<OptionValue> values;
    for (const po::option& option : parsed.options) {
        if (findBuildOption(option.string_key, OptionSpelling::CommandLine) == nullptr)
            continue; // --quiet, --json, --help: the CLI's own
        if (option.value.empty())
            values.push_back({option.string_key, "true"});
        for (const std::string& text : option.value)
            values.push_back({option.string_key, text});
    }
    return values;
}

// GDAL's programs spell these with one dash; terratin's long options take two.
std::string gdalHabit(const std::string& word) {
    if (word == "of")
        return "--format";
    if (word == "a_srs")
        return "--s_srs";
    return "";
}

// The long option a single-dash word means: the same name, a GDAL habit, or a close name.
std::string meantOption(const std::string& word) {
    if (const BuildOptionSpec* option = findBuildOption(word, OptionSpelling::CommandLine))
        return "--" + std::string(option->longFlag);
    if (std::string habit = gdalHabit(word); !habit.empty())
        return habit;
    if (word == "quiet" || word == "json" || word == "help")
        return "--" + word;
    return closestBuildOption("--" + word, OptionSpelling::CommandLine);
}

// Whether `argument`, an option, takes the next argument as its value.
bool takesNextValue(const std::string& argument) {
    if (argument.find('=') != std::string::npos)
        return false;
    const std::string name = argument.substr(argument.starts_with("--") ? 2 : 1);
    const BuildOptionSpec* option = nullptr;
    if (name.size() == 1) {
        for (const BuildOptionSpec& candidate : buildOptionTable())
            if (candidate.shortFlag == name.front())
                option = &candidate;
    } else {
        option = findBuildOption(name, OptionSpelling::CommandLine);
    }
    return option != nullptr && option->kind != OptionKind::Flag;
}

// Boost reads "-of GPKG" as "-o f" and "-ooverwrite.fgb" as "-o overwrite.fgb": a habit of GDAL
// users that would silently name the output. One-letter options and their value are therefore
// kept apart, and a word after one dash is refused with the option it likely means.
void refuseSingleDashWords(const std::vector<std::string>& arguments) {
    bool valueNext = false;
    for (const std::string& argument : arguments) {
        if (valueNext) {
            valueNext = false;
            continue;
        }
        const bool singleDashWord = argument.size() > 2 && argument[0] == '-' &&
                                    std::isalpha(static_cast<unsigned char>(argument[1])) != 0;
        if (singleDashWord) {
            const std::string meant = meantOption(argument.substr(1));
            throw UsageError("'" + argument +
                             "': an option of one dash is one letter, with its value after a "
                             "space (-o FILE); long options take two dashes" +
                             (meant.empty() ? std::string() : ": did you mean '" + meant + "'?"));
        }
        if (argument.starts_with("-"))
            valueNext = takesNextValue(argument);
    }
}

std::string formatsText() {
    std::ostringstream text;
    text << "Output formats (--format NAME, or the output's extension):\n";
    for (const io::TinFormatInfo& format : io::tinFormats())
        text << "  " << format.name() << std::string(9 - format.name().size(), ' ')
             << format.extensions << std::string(15 - format.extensions.size(), ' ')
             << format.carries << "\n";
    return text.str();
}

std::string helpText(const po::options_description& options) {
    std::ostringstream text;
    text << kUsage << "\n" << kDescription << "\n" << options;
    return text.str();
}

// What a first argument other than `build` asks for: the help, the version or the formats.
Command::Kind infoCommand(const std::string& verb) {
    if (verb == "--help" || verb == "-h" || verb == "help")
        return Command::Kind::Help;
    if (verb == "--version")
        return Command::Kind::Version;
    if (verb == "--formats")
        return Command::Kind::Formats;
    throw UsageError("unknown command '" + verb + "'; try 'terratin --help'");
}

// The arguments after `build` as Boost read them, and the library's options among them.
struct BuildArguments {
    po::variables_map values;
    std::vector<OptionValue> given;
};

// Reads `rest` against `options` and the inputs (the positional arguments). Every mistake Boost
// finds is a UsageError; an unknown option's names the closest one.
BuildArguments readBuildArguments(const std::vector<std::string>& rest,
                                  const po::options_description& options) {
    const std::string inputName(findBuildOption("inputs", OptionSpelling::Keyword)->longFlag);
    po::options_description all;
    all.add(options);
    all.add_options()(inputName.c_str(), po::value<std::vector<std::string>>());
    po::positional_options_description positional;
    positional.add(inputName.c_str(), -1);

    BuildArguments read;
    try {
        refuseSingleDashWords(rest);
        const po::parsed_options parsed =
            po::command_line_parser(rest).options(all).positional(positional).run();
        po::store(parsed, read.values); // refuses an option given twice
        po::notify(read.values);
        read.given = tableValues(parsed);
    } catch (const po::unknown_option& error) {
        const std::string typed = error.get_option_name();
        const std::string closest = closestBuildOption(typed, OptionSpelling::CommandLine);
        throw UsageError(error.what() +
                         (closest.empty() ? std::string() : "; did you mean '" + closest + "'?"));
    } catch (const po::error& error) {
        throw UsageError(error.what());
    }
    return read;
}

// The build's options from what the user typed. Every value the library refuses, and options
// that contradict each other or the output format, are command-line mistakes (status 2).
BuildOptions checkedBuildOptions(const std::vector<OptionValue>& given) {
    try {
        return parseBuildOptions(given, OptionSpelling::CommandLine);
    } catch (const Error& error) {
        throw UsageError(error.what());
    }
}

} // namespace

Command parseCommandLine(const std::vector<std::string>& arguments) {
    Command command;
    const po::options_description options = buildOptionsDescription();
    command.helpText = helpText(options);
    if (arguments.empty())
        throw UsageError("missing command; try 'terratin --help'");
    const std::string& verb = arguments.front();
    if (verb != "build") {
        command.kind = infoCommand(verb);
        if (command.kind == Command::Kind::Formats)
            command.helpText = formatsText();
        return command;
    }

    const BuildArguments read =
        readBuildArguments({arguments.begin() + 1, arguments.end()}, options);
    if (read.values.count("help")) {
        command.kind = Command::Kind::Help;
        return command;
    }
    command.kind = Command::Kind::Build;
    command.build = checkedBuildOptions(read.given);
    command.quiet = read.values.count("quiet") > 0;
    command.json = read.values.count("json") > 0;
    return command;
}

} // namespace terratin::cli

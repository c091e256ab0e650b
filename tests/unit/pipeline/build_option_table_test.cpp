// The build options parsed from text by the library: every option, both spellings of every
// message, unknown names, and the CLI giving what the library gives.

#include "terratin/pipeline/build_option_table.hpp"

#include "cli_options.hpp"
#include "temporary_directory.hpp"
#include "terratin/error.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <set>
#include <string>
#include <vector>

namespace terratin {
namespace {

// Every field parseBuildOptions can set (not `notice`, a callback).
void expectSameOptions(const BuildOptions& a, const BuildOptions& b) {
    EXPECT_EQ(a.inputs, b.inputs);
    EXPECT_EQ(a.output, b.output);
    EXPECT_EQ(a.format, b.format);
    EXPECT_EQ(a.band, b.band);
    EXPECT_EQ(a.overwrite, b.overwrite);
    EXPECT_EQ(a.triangulation.seed, b.triangulation.seed);
    EXPECT_EQ(a.triangulation.order, b.triangulation.order);
    EXPECT_EQ(a.triangulation.duplicateZ, b.triangulation.duplicateZ);
    EXPECT_EQ(a.triangulation.method, b.triangulation.method);
    EXPECT_EQ(a.triangulation.locate, b.triangulation.locate);
    EXPECT_EQ(a.triangulation.threads, b.triangulation.threads);
    EXPECT_EQ(a.triangulation.searchers, b.triangulation.searchers);
    EXPECT_EQ(a.triangulation.queueLength, b.triangulation.queueLength);
    EXPECT_EQ(a.triangulation.searchersHelpWhenQueueFull,
              b.triangulation.searchersHelpWhenQueueFull);
    EXPECT_EQ(a.validate, b.validate);
    EXPECT_EQ(a.layerName, b.layerName);
    EXPECT_EQ(a.lasClasses, b.lasClasses);
    EXPECT_EQ(a.lasReturns, b.lasReturns);
    EXPECT_EQ(a.textColumns, b.textColumns);
    EXPECT_EQ(a.zField, b.zField);
    EXPECT_EQ(a.inputLayer, b.inputLayer);
    EXPECT_EQ(a.sourceSrs, b.sourceSrs);
    EXPECT_EQ(a.targetSrs, b.targetSrs);
    EXPECT_EQ(a.keepGeographic, b.keepGeographic);
    EXPECT_EQ(a.zFactor, b.zFactor);
    EXPECT_EQ(a.optionSpelling, b.optionSpelling);
    ASSERT_EQ(a.refine.has_value(), b.refine.has_value());
    if (a.refine) {
        EXPECT_EQ(a.refine->maxError, b.refine->maxError);
        EXPECT_EQ(a.refine->maxPoints, b.refine->maxPoints);
        EXPECT_EQ(a.refine->maxTriangles, b.refine->maxTriangles);
        EXPECT_EQ(a.refine->maxHole, b.refine->maxHole);
        EXPECT_EQ(a.refine->fillHoles, b.refine->fillHoles);
    }
    EXPECT_EQ(a.maxEdge, b.maxEdge);
    EXPECT_EQ(a.attributes, b.attributes);
    EXPECT_EQ(a.nodes, b.nodes);
    EXPECT_EQ(a.edges, b.edges);
    EXPECT_EQ(a.appendLayer, b.appendLayer);
    EXPECT_EQ(a.spatialIndex, b.spatialIndex);
    EXPECT_EQ(a.qgisStyle, b.qgisStyle);
}

// The message of the InvalidInputError `parse` throws; "" when it throws none.
template <class Parse> std::string messageOf(Parse parse) {
    try {
        parse();
    } catch (const InvalidInputError& error) {
        return error.what();
    }
    return "";
}

// `keyword`'s name in `spelling`, as a caller of that spelling writes it.
std::string nameIn(OptionSpelling spelling, const std::string& keyword) {
    return optionName(keyword, spelling);
}

// inputs and output, the two options every build needs, then `rest`, all by keyword.
std::vector<OptionValue> withInputAndOutput(std::vector<OptionValue> rest) {
    std::vector<OptionValue> values = {{"inputs", "dem.tif"}, {"output", "tin.gpkg"}};
    values.insert(values.end(), rest.begin(), rest.end());
    return values;
}

// `values` (by keyword) named as a caller of `spelling` names them: "--max-error" / "max_error"
// (the inputs: "input", the key of the CLI's positional arguments).
std::vector<OptionValue> spelled(std::vector<OptionValue> values, OptionSpelling spelling) {
    if (spelling == OptionSpelling::Keyword)
        return values;
    for (OptionValue& value : values)
        value.name =
            "--" + std::string(findBuildOption(value.name, OptionSpelling::Keyword)->longFlag);
    return values;
}

TEST(BuildOptionTable, NamesAreUniqueAndEveryOptionIsDocumented) {
    std::set<std::string_view> keywords;
    std::set<std::string_view> flags;
    for (const BuildOptionSpec& option : buildOptionTable()) {
        EXPECT_TRUE(keywords.insert(option.keyword).second) << option.keyword;
        EXPECT_TRUE(flags.insert(option.longFlag).second) << option.longFlag;
        EXPECT_EQ(option.keyword.find('-'), std::string_view::npos) << option.keyword;
        EXPECT_FALSE(option.help.empty()) << option.keyword;
        EXPECT_NE(option.apply, nullptr) << option.keyword;
        EXPECT_EQ(option.valueName.empty(), option.kind == OptionKind::Flag) << option.keyword;
    }
    // The inputs and every option of `terratin build --help` but the CLI's own (quiet, json,
    // help).
    EXPECT_EQ(keywords.size(), 47U);
}

std::uint64_t memoryLimitFrom(const std::string& text) {
    BuildOptions options;
    applyBuildOption(options, {"memory_limit", text}, OptionSpelling::Keyword);
    return *options.memoryLimit;
}

TEST(ParseBuildOptions, ParsesMemoryLimits_InPowersOf1024) {
    EXPECT_EQ(memoryLimitFrom("2G"), std::uint64_t{2} << 30U);
    EXPECT_EQ(memoryLimitFrom("512m"), std::uint64_t{512} << 20U);
    EXPECT_EQ(memoryLimitFrom("1.5GiB"), std::uint64_t{3} << 29U);
    EXPECT_EQ(memoryLimitFrom("64KB"), std::uint64_t{64} << 10U);
    EXPECT_EQ(memoryLimitFrom("1T"), std::uint64_t{1} << 40U);
    EXPECT_EQ(memoryLimitFrom("1000000"), 1'000'000U);
    for (const char* bad : {"", "G", "0", "-1G", "2X", "2GG", "1.5.2M", "0.1", "inf", "1e30G"})
        EXPECT_THROW(memoryLimitFrom(bad), InvalidInputError) << bad;
}

TEST(BuildOptionTable, DefaultTextParsesToTheDefault) {
    const BuildOptions defaults;
    for (const BuildOptionSpec& option : buildOptionTable()) {
        if (option.defaultText.empty())
            continue;
        BuildOptions parsed;
        applyBuildOption(parsed, {std::string(option.keyword), std::string(option.defaultText)},
                         OptionSpelling::Keyword);
        SCOPED_TRACE(std::string(option.keyword));
        expectSameOptions(parsed, defaults);
    }
}

TEST(BuildOptionTable, OptionNames_FollowTheSpelling) {
    EXPECT_EQ(optionName("max_error", OptionSpelling::CommandLine), "--max-error");
    EXPECT_EQ(optionName("max_error", OptionSpelling::Keyword), "max_error");
    EXPECT_EQ(optionName("t_srs", OptionSpelling::CommandLine), "--t_srs");
    EXPECT_EQ(optionName("inputs", OptionSpelling::CommandLine), "INPUT");
    EXPECT_EQ(optionName("inputs", OptionSpelling::Keyword), "inputs");
    EXPECT_EQ(optionName("classes", OptionSpelling::CommandLine), "--class");
    EXPECT_THROW(optionName("max-error", OptionSpelling::Keyword), Error);
    EXPECT_NE(findBuildOption("--max-error", OptionSpelling::CommandLine), nullptr);
    EXPECT_NE(findBuildOption("max-error", OptionSpelling::CommandLine), nullptr);
    EXPECT_EQ(findBuildOption("max-error", OptionSpelling::Keyword), nullptr);
}

// The LAS returns and the attribute sets were parsed by io::parseLasReturns and
// io::parseAttributeSet too, until the option table became their one parser.
io::LasReturns returnsFrom(const std::string& text) {
    BuildOptions options;
    applyBuildOption(options, {"returns", text}, OptionSpelling::Keyword);
    return options.lasReturns;
}

io::AttributeSet attributesFrom(const std::string& text) {
    BuildOptions options;
    applyBuildOption(options, {"attributes", text}, OptionSpelling::Keyword);
    return options.attributes;
}

TEST(ParseBuildOptions, ParsesReturns_WhenCaseDiffers) {
    EXPECT_EQ(returnsFrom("FIRST"), io::LasReturns::First);
    EXPECT_EQ(returnsFrom("last"), io::LasReturns::Last);
    EXPECT_EQ(returnsFrom("all"), io::LasReturns::All);
    EXPECT_THROW(returnsFrom("second"), InvalidInputError);
}

TEST(ParseBuildOptions, ParsesNoneBasicAll_WhenCaseDiffers) {
    EXPECT_EQ(attributesFrom("none"), io::AttributeSet::None);
    EXPECT_EQ(attributesFrom("Basic"), io::AttributeSet::Basic);
    EXPECT_EQ(attributesFrom("ALL"), io::AttributeSet::All);
    EXPECT_THROW(attributesFrom("some"), InvalidInputError);
}

TEST(ParseBuildOptions, ParsesEveryOptionFromText) {
    const BuildOptions options = parseBuildOptions({{"inputs", "a.las"},
                                                    {"inputs", "b.xyz"},
                                                    {"output", "out.fgb"},
                                                    {"format", "FlatGeobuf"},
                                                    {"band", "2"},
                                                    {"seed", "18446744073709551615"},
                                                    {"order", "Random"},
                                                    {"duplicate_z", "mean"},
                                                    {"method", "batch"},
                                                    {"locate", "walk"},
                                                    {"threads", "4"},
                                                    {"searchers", "2"},
                                                    {"queue_length", "64"},
                                                    {"searchers_help", "true"},
                                                    {"max_edge", "12.5"},
                                                    {"layer", "surface"},
                                                    {"attributes", "basic"},
                                                    {"qgis_style", "TRUE"},
                                                    {"classes", "2,9"},
                                                    {"classes", "6"},
                                                    {"returns", "last"},
                                                    {"columns", "E,N,H"},
                                                    {"z_field", "elev"},
                                                    {"input_layer", "spots"},
                                                    {"s_srs", "EPSG:4326"},
                                                    {"t_srs", "EPSG:32619"},
                                                    {"z_factor", "0.3048"},
                                                    {"overwrite", "true"},
                                                    {"validate", "true"},
                                                    {"breaklines", "roads.gpkg"},
                                                    {"breaklines", "rivers.shp"},
                                                    {"breaklines_layer", "lines"},
                                                    {"breakline_z", "Surface"},
                                                    {"clip", "area.gpkg"},
                                                    {"erase", "lakes.gpkg|layername=lakes"},
                                                    {"replace", "water.shp"},
                                                    {"replace_z_field", "level"}},
                                                   OptionSpelling::Keyword);
    EXPECT_EQ(options.inputs, (std::vector<std::string>{"a.las", "b.xyz"}));
    EXPECT_EQ(options.output, "out.fgb");
    EXPECT_EQ(options.format, io::TinFormat::FlatGeobuf);
    EXPECT_EQ(options.band, 2);
    EXPECT_EQ(options.triangulation.seed, 18446744073709551615ULL);
    EXPECT_EQ(options.triangulation.order, InsertionOrder::Random);
    EXPECT_EQ(options.triangulation.duplicateZ, DuplicateZPolicy::Mean);
    EXPECT_EQ(options.triangulation.method, TriangulationMethod::Batch);
    EXPECT_EQ(options.triangulation.locate, PointLocation::Walk);
    EXPECT_EQ(options.triangulation.threads, 4U);
    EXPECT_EQ(options.triangulation.searchers, 2U);
    EXPECT_EQ(options.triangulation.queueLength, 64U);
    EXPECT_TRUE(options.triangulation.searchersHelpWhenQueueFull);
    EXPECT_EQ(options.maxEdge, 12.5);
    EXPECT_EQ(options.layerName, "surface");
    EXPECT_EQ(options.attributes, io::AttributeSet::Basic);
    EXPECT_TRUE(options.qgisStyle);
    EXPECT_EQ(options.lasClasses, (std::vector<int>{2, 9, 6}));
    EXPECT_EQ(options.lasReturns, io::LasReturns::Last);
    EXPECT_EQ(options.textColumns, (std::vector<std::string>{"E", "N", "H"}));
    EXPECT_EQ(options.zField, "elev");
    EXPECT_EQ(options.inputLayer, "spots");
    EXPECT_EQ(options.sourceSrs, "EPSG:4326");
    EXPECT_EQ(options.targetSrs, "EPSG:32619");
    EXPECT_EQ(options.zFactor, 0.3048);
    EXPECT_TRUE(options.overwrite);
    EXPECT_TRUE(options.validate);
    EXPECT_EQ(options.breaklines, (std::vector<std::string>{"roads.gpkg", "rivers.shp"}));
    EXPECT_EQ(options.breaklinesLayer, "lines");
    EXPECT_EQ(options.breaklineZ, BreaklineZ::Surface);
    EXPECT_EQ(options.clip, "area.gpkg");
    EXPECT_EQ(options.erase, "lakes.gpkg|layername=lakes");
    EXPECT_EQ(options.replace, "water.shp");
    EXPECT_EQ(options.replaceZField, "level");
    EXPECT_FALSE(options.refine);
    EXPECT_EQ(options.optionSpelling, OptionSpelling::Keyword);
}

TEST(ParseBuildOptions, SimplificationOptionsSwitchRefineOn) {
    const BuildOptions options = parseBuildOptions(withInputAndOutput({{"max_error", "0.5"},
                                                                       {"max_points", "1000"},
                                                                       {"max_triangles", "2000"},
                                                                       {"fill_holes", "true"}}),
                                                   OptionSpelling::Keyword);
    ASSERT_TRUE(options.refine);
    EXPECT_EQ(options.refine->maxError, 0.5);
    EXPECT_EQ(options.refine->maxPoints, 1000U);
    EXPECT_EQ(options.refine->maxTriangles, 2000U);
    EXPECT_TRUE(options.refine->fillHoles);
    EXPECT_EQ(parseBuildOptions(withInputAndOutput({{"max_hole", "0"}}), OptionSpelling::Keyword)
                  .refine->maxHole,
              0U);
    for (const char* keyword : {"max_error", "max_points", "max_triangles", "max_hole"})
        EXPECT_TRUE(
            parseBuildOptions(withInputAndOutput({{keyword, "7"}}), OptionSpelling::Keyword).refine)
            << keyword;
}

TEST(ParseBuildOptions, RefusesMaxHoleWithFillHoles_WhichContradictIt) {
    try {
        parseBuildOptions(withInputAndOutput({{"max_hole", "3"}, {"fill_holes", "true"}}),
                          OptionSpelling::Keyword);
        ADD_FAILURE() << "max_hole with fill_holes was taken";
    } catch (const InvalidInputError& error) {
        EXPECT_STREQ(error.what(), "max_hole and fill_holes contradict each other: give one");
    }
    // fill_holes=false leaves max_hole its meaning.
    EXPECT_EQ(parseBuildOptions(withInputAndOutput({{"max_hole", "3"}, {"fill_holes", "false"}}),
                                OptionSpelling::Keyword)
                  .refine->maxHole,
              3U);
}

TEST(ParseBuildOptions, FlagsTakeFalse_AndFillHolesFalseAloneDoesNotSimplify) {
    const BuildOptions options =
        parseBuildOptions(withInputAndOutput({{"overwrite", "true"},
                                              {"overwrite", "false"},
                                              {"no_spatial_index", "false"},
                                              {"fill_holes", "false"}}),
                          OptionSpelling::Keyword);
    EXPECT_FALSE(options.overwrite);
    EXPECT_TRUE(options.spatialIndex);
    EXPECT_FALSE(options.refine);
}

TEST(ParseBuildOptions, FormatFollowsTheOutputsExtension_WhenNotGiven) {
    EXPECT_EQ(
        parseBuildOptions({{"inputs", "dem.tif"}, {"output", "tin.ply"}}, OptionSpelling::Keyword)
            .format,
        io::TinFormat::Ply);
    EXPECT_THROW(
        parseBuildOptions({{"inputs", "dem.tif"}, {"output", "tin.abc"}}, OptionSpelling::Keyword),
        InvalidInputError);
}

struct BadValue {
    std::string keyword;
    std::string text;
    /// The message, with {} where the option's name goes.
    std::string message;
};

std::string named(std::string message, const std::string& name) {
    return message.replace(message.find("{}"), 2, name);
}

TEST(ParseBuildOptions, RefusesBadValues_NamingTheOptionInBothSpellings) {
    const std::vector<BadValue> cases = {
        {"band", "x", "the argument ('x') for option '{}' is invalid"},
        {"band", "0", "{} must be 1 or more"},
        {"seed", "-1", "{} takes a whole number without sign (got '-1')"},
        {"seed", "99999999999999999999", "{} is too large (got '99999999999999999999')"},
        {"threads", "+1", "{} takes a whole number without sign (got '+1')"},
        {"threads", "", "{} takes a whole number without sign (got '')"},
        {"queue_length", "1k", "{} takes a whole number without sign (got '1k')"},
        {"max_points", "-5", "{} takes a whole number without sign (got '-5')"},
        {"order", "Hilbert", "{} must be brio or random (got 'Hilbert')"},
        {"locate", "jump", "{} must be dag or walk (got 'jump')"},
        {"method", "fast",
         "{} must be sequential, batch, circumcircle, strips or auto (got 'fast')"},
        {"duplicate_z", "median", "{} must be first, last, min, max or mean (got 'median')"},
        {"attributes", "some", "{} must be none, basic or all (got 'some')"},
        {"returns", "second", "{} must be first, last or all (got 'second')"},
        {"max_error", "nan", "{} must be a finite number >= 0"},
        {"max_error", "-1", "{} must be a finite number >= 0"},
        {"max_error", "1e400", "the argument ('1e400') for option '{}' is invalid"},
        {"max_edge", "0", "{} must be a positive number"},
        {"max_edge", "inf", "{} must be a positive number"},
        {"z_factor", "0", "{} must be a finite number other than 0"},
        {"z_factor", "-inf", "{} must be a finite number other than 0"},
        {"classes", "ground", "{} takes classification codes 0..255 (got 'ground')"},
        {"classes", "2,256", "{} takes classification codes 0..255 (got '256')"},
        {"classes", "2,", "{} takes classification codes 0..255 (got '')"},
        {"columns", "1,2", "{} takes three columns x,y,z (got '1,2')"},
        {"columns", "0,1,2", "{}: columns are numbered from 1"},
        {"t_srs", " ", "{} needs a CRS (EPSG:n, WKT, PROJ string, .prj file), not an empty string"},
        {"s_srs", "", "{} needs a CRS (EPSG:n, WKT, PROJ string, .prj file), not an empty string"},
        {"validate", "yes", "{} takes true or false (got 'yes')"},
        {"breakline_z", "sky", "{} must be line or surface (got 'sky')"},
        {"breaklines", "", "{} needs a file name"},
    };
    for (const OptionSpelling spelling : {OptionSpelling::CommandLine, OptionSpelling::Keyword})
        for (const BadValue& bad : cases) {
            const std::string name = nameIn(spelling, bad.keyword);
            EXPECT_EQ(messageOf([&] {
                          parseBuildOptions(
                              spelled(withInputAndOutput({{bad.keyword, bad.text}}), spelling),
                              spelling);
                      }),
                      named(bad.message, name))
                << name << " " << bad.text;
        }
}

TEST(ParseBuildOptions, RefusesContradictions_NamingTheOptionsInBothSpellings) {
    const std::vector<OptionValue> values =
        withInputAndOutput({{"keep_geographic", "true"}, {"t_srs", "EPSG:3857"}});
    EXPECT_EQ(messageOf([&] {
                  parseBuildOptions(spelled(values, OptionSpelling::CommandLine),
                                    OptionSpelling::CommandLine);
              }),
              "--keep-geographic and --t_srs contradict each other");
    EXPECT_EQ(messageOf([&] { parseBuildOptions(values, OptionSpelling::Keyword); }),
              "keep_geographic and t_srs contradict each other");
}

TEST(ParseBuildOptions, RefusesMissingInputsAndOutput_InBothSpellings) {
    EXPECT_EQ(messageOf([] {
                  parseBuildOptions({{"--output", "tin.gpkg"}}, OptionSpelling::CommandLine);
              }),
              "missing INPUT");
    EXPECT_EQ(messageOf([] {
                  parseBuildOptions({{"output", "tin.gpkg"}}, OptionSpelling::Keyword);
              }),
              "missing inputs");
    EXPECT_EQ(messageOf([] {
                  parseBuildOptions({{"input", "dem.tif"}}, OptionSpelling::CommandLine);
              }),
              "missing -o OUTPUT");
    EXPECT_EQ(messageOf([] {
                  parseBuildOptions({{"inputs", "dem.tif"}}, OptionSpelling::Keyword);
              }),
              "missing output");
}

TEST(ParseBuildOptions, RefusesUnknownNames_SuggestingTheClosest) {
    EXPECT_EQ(
        messageOf([] {
            parseBuildOptions(withInputAndOutput({{"max_eror", "1"}}), OptionSpelling::Keyword);
        }),
        "unknown option 'max_eror'; did you mean 'max_error'?");
    // A command-line spelling given as a keyword is unknown too, and points at the keyword.
    EXPECT_EQ(
        messageOf([] {
            parseBuildOptions(withInputAndOutput({{"z-factor", "2"}}), OptionSpelling::Keyword);
        }),
        "unknown option 'z-factor'; did you mean 'z_factor'?");
    EXPECT_EQ(messageOf([] {
                  parseBuildOptions(withInputAndOutput({{"colour_ramp", "terrain"}}),
                                    OptionSpelling::Keyword);
              }),
              "unknown option 'colour_ramp'");
    BuildOptions options;
    EXPECT_EQ(messageOf([&] {
                  applyBuildOption(options, {"--max-eror", "1"}, OptionSpelling::CommandLine);
              }),
              "unknown option '--max-eror'; did you mean '--max-error'?");
}

TEST(ParseBuildOptions, LibraryRangeChecksNameNoFlag) {
    for (const OptionSpelling spelling : {OptionSpelling::CommandLine, OptionSpelling::Keyword}) {
        const std::string message = messageOf([&] {
            parseBuildOptions(spelled(withInputAndOutput({{"threads", "100000"}}), spelling),
                              spelling);
        });
        EXPECT_EQ(message.rfind("Triangulator: the thread count must be 0 (all) to ", 0), 0U)
            << message;
    }
}

// An error carries the options it names as keywords (data), and each caller names them its way.
TEST(OptionMessages, AnErrorCarriesItsOptionsAsKeywords_AndEachCallerNamesThem) {
    InvalidInputError error("Build: " + markOption("tiles_dir") + " writes tiles: give " +
                            markOption("tile_size"));
    EXPECT_EQ(error.options(), (std::vector<std::string>{"tiles_dir", "tile_size"}));
    EXPECT_STREQ(error.what(), "Build: tiles_dir writes tiles: give tile_size");
    error.nameOptions(optionNaming(OptionSpelling::CommandLine));
    EXPECT_STREQ(error.what(), "Build: --tiles-dir writes tiles: give --tile-size");
    // A message wrapping it keeps the marks, so the options are still named at the top.
    InvalidInputError wrapped("Input: " + error.markedMessage());
    wrapped.nameOptions(optionNaming(OptionSpelling::Keyword));
    EXPECT_STREQ(wrapped.what(), "Input: Build: tiles_dir writes tiles: give tile_size");
}

// keep_geographic with t_srs was refused only when parsed from text: a C++ caller filling
// BuildOptions in had t_srs silently ignored.
TEST(CheckBuildOptions, RefusesKeepGeographicWithATargetCrs_ForACallerThatDidNotParse) {
    BuildOptions options;
    options.inputs = {"dem.tif"};
    options.output = "tin.gpkg";
    options.keepGeographic = true;
    options.targetSrs = "EPSG:32633";
    EXPECT_EQ(messageOf([&] { checkBuildOptions(options); }),
              "keep_geographic and t_srs contradict each other");
    options.optionSpelling = OptionSpelling::CommandLine;
    EXPECT_EQ(messageOf([&] { runBuild(options); }),
              "--keep-geographic and --t_srs contradict each other");
}

// runBuild's own messages name options the way parseBuildOptions was called.
TEST(ParseBuildOptions, RunBuildMessagesFollowTheSpelling) {
    test::TemporaryDirectory directory;
    const std::string output = (directory.path() / "tin.gpkg").string();
    const std::vector<OptionValue> values = {
        {"inputs", "dem.tif"}, {"output", output}, {"max_error", "1"}, {"z_factor", "2"}};
    EXPECT_EQ(messageOf([&] {
                  runBuild(parseBuildOptions(spelled(values, OptionSpelling::CommandLine),
                                             OptionSpelling::CommandLine));
              }),
              "Simplification (--max-error...) does not combine with --z-factor; scale the DEM "
              "first (gdal_calc)");
    EXPECT_EQ(messageOf([&] { runBuild(parseBuildOptions(values, OptionSpelling::Keyword)); }),
              "Simplification (max_error...) does not combine with z_factor; scale the DEM "
              "first (gdal_calc)");
}

// The writer's messages (io, below the pipeline) name options the way parseBuildOptions was
// called, through BuildOptions::optionSpelling.
TEST(ParseBuildOptions, WriterMessagesFollowTheSpelling) {
    test::TemporaryDirectory directory;
    const std::string existing = (directory.path() / "tin.gpkg").string();
    std::ofstream(existing) << "someone's";
    struct Case {
        std::vector<OptionValue> values;
        std::string commandLine;
        std::string keyword;
    };
    const std::vector<Case> cases = {
        {{{"inputs", "dem.tif"}, {"output", "tin.shp"}, {"nodes", "true"}},
         "TinWriter: --nodes needs a GeoPackage output (.gpkg), not ESRI Shapefile",
         "TinWriter: nodes needs a GeoPackage output (.gpkg), not ESRI Shapefile"},
        {{{"inputs", "dem.tif"}, {"output", "tin.ply"}, {"no_spatial_index", "true"}},
         "TinWriter: --no-spatial-index applies to GeoPackage and FlatGeobuf, not PLY",
         "TinWriter: no_spatial_index applies to GeoPackage and FlatGeobuf, not PLY"},
        {{{"inputs", "dem.tif"},
          {"output", "tin.gpkg"},
          {"qgis_style", "true"},
          {"attributes", "none"}},
         "TinWriter: --qgis-style colours by z_mean: it needs --attributes basic or all",
         "TinWriter: qgis_style colours by z_mean: it needs attributes basic or all"},
        {{{"inputs", "dem.tif"}, {"output", "tin.stl"}},
         "TinFormat: cannot tell the output format of 'tin.stl' from its extension; use .gpkg "
         ".shp .fgb .2dm .ply .obj .xml .landxml (or --format)",
         "TinFormat: cannot tell the output format of 'tin.stl' from its extension; use .gpkg "
         ".shp .fgb .2dm .ply .obj .xml .landxml (or format)"},
        {{{"inputs", "dem.tif"}, {"output", existing}},
         "OgrTinWriter: the output '" + existing + "' exists; use --overwrite",
         "OgrTinWriter: the output '" + existing + "' exists; use overwrite"},
    };
    for (const Case& c : cases) {
        EXPECT_EQ(messageOf([&] {
                      runBuild(parseBuildOptions(spelled(c.values, OptionSpelling::CommandLine),
                                                 OptionSpelling::CommandLine));
                  }),
                  c.commandLine);
        EXPECT_EQ(
            messageOf([&] { runBuild(parseBuildOptions(c.values, OptionSpelling::Keyword)); }),
            c.keyword);
    }
}

TEST(ParseBuildOptions, CommandLineGivesWhatTheLibraryGives) {
    const cli::Command command = cli::parseCommandLine({"build",
                                                        "a.las",
                                                        "-o",
                                                        "out.gpkg",
                                                        "b.xyz",
                                                        "--max-error",
                                                        "0.5",
                                                        "-j",
                                                        "3",
                                                        "--method",
                                                        "Strips",
                                                        "--class",
                                                        "2,9",
                                                        "--class",
                                                        "6",
                                                        "--columns",
                                                        "1,2,3",
                                                        "--t_srs",
                                                        "EPSG:32619",
                                                        "--fill-holes",
                                                        "--nodes",
                                                        "--no-spatial-index",
                                                        "--attributes",
                                                        "basic",
                                                        "-b",
                                                        "1",
                                                        "--z-factor",
                                                        "1",
                                                        "--layer",
                                                        "surface",
                                                        "--quiet"});
    ASSERT_EQ(command.kind, cli::Command::Kind::Build);
    EXPECT_TRUE(command.quiet);
    const BuildOptions byKeyword = parseBuildOptions({{"inputs", "a.las"},
                                                      {"output", "out.gpkg"},
                                                      {"inputs", "b.xyz"},
                                                      {"max_error", "0.5"},
                                                      {"threads", "3"},
                                                      {"method", "Strips"},
                                                      {"classes", "2,9"},
                                                      {"classes", "6"},
                                                      {"columns", "1,2,3"},
                                                      {"t_srs", "EPSG:32619"},
                                                      {"fill_holes", "true"},
                                                      {"nodes", "true"},
                                                      {"no_spatial_index", "true"},
                                                      {"attributes", "basic"},
                                                      {"band", "1"},
                                                      {"z_factor", "1"},
                                                      {"layer", "surface"}},
                                                     OptionSpelling::Keyword);
    BuildOptions expected = byKeyword;
    expected.optionSpelling = OptionSpelling::CommandLine;
    expectSameOptions(command.build, expected);
}

TEST(ParseBuildOptions, CommandLineRefusesWhatTheLibraryRefuses_WithTheSameMessage) {
    try {
        cli::parseCommandLine({"build", "dem.tif", "-o", "out.gpkg", "--method", "fast"});
        FAIL() << "no usage error";
    } catch (const cli::UsageError& error) {
        EXPECT_STREQ(error.what(),
                     "--method must be sequential, batch, circumcircle, strips or auto (got "
                     "'fast')");
    }
}

} // namespace
} // namespace terratin

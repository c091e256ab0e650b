// The writer's messages name options the caller's way. The error carries each option's keyword
// (markOption): a C++ caller reads keywords ("overwrite"), never a command-line flag; a caller
// that names them its own way (Error::nameOptions; runBuild: "--overwrite" for the command
// line) reads its names.

#include "terratin/error.hpp"
#include "terratin/io/tin_format.hpp"
#include "terratin/io/tin_writer.hpp"

#include "mesh_readers.hpp"
#include "ogr_test_support.hpp"
#include "temporary_directory.hpp"

#include <gtest/gtest.h>

#include <cstddef>
#include <fstream>
#include <functional>
#include <set>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace terratin::io {
namespace {

using test::TemporaryDirectory;

/// How the tests' own caller names options: "<overwrite>". Appended piecewise: GCC 12 reports a
/// spurious -Wrestrict for "<" + string + ">".
std::string bracketed(std::string_view keyword) {
    std::string name = "<";
    name += keyword;
    name += '>';
    return name;
}

/// A caller's naming of options (empty: by keyword), and how it names the keyword `{keyword}`
/// in a message pattern.
struct Naming {
    std::string label;
    OptionNaming naming;
    std::function<std::string(const std::string&)> name;
};

std::vector<Naming> namings() {
    return {{"keywords", OptionNaming(), [](const std::string& keyword) { return keyword; }},
            {"the caller's names", OptionNaming(bracketed),
             [](const std::string& keyword) { return bracketed(keyword); }}};
}

/// `pattern` with each "{keyword}" replaced by naming.name(keyword).
std::string spelled(const std::string& pattern, const Naming& naming) {
    std::string text;
    std::size_t from = 0;
    for (std::size_t open = pattern.find('{'); open != std::string::npos;
         open = pattern.find('{', from)) {
        const std::size_t close = pattern.find('}', open);
        text += pattern.substr(from, open - from) +
                naming.name(pattern.substr(open + 1, close - open - 1));
        from = close + 1;
    }
    return text + pattern.substr(from);
}

/// The message of the InvalidInputError `call` throws, its options named the `naming` way; ""
/// when it throws none.
std::string refusal(const std::function<void()>& call, const OptionNaming& naming = {}) {
    try {
        call();
    } catch (InvalidInputError& error) {
        error.nameOptions(naming);
        return error.what();
    }
    return {};
}

/// Checks that `message` holds `pattern` spelled the `naming` way, and no command-line flag
/// unless the caller named options so.
void expectSpelled(const std::string& message, const std::string& pattern, const Naming& naming) {
    EXPECT_NE(message.find(spelled(pattern, naming)), std::string::npos)
        << naming.label << ": " << message;
    EXPECT_EQ(message.find("--"), std::string::npos) << naming.label << ": " << message;
}

TinWriteOptions optionsFor(TinFormat format, const Naming& naming) {
    TinWriteOptions options;
    options.format = format;
    options.crsWkt = test::utm10nWkt();
    return options;
}

TEST(WriterMessages, NameContradictoryOptionsTheCallersWay) {
    struct Case {
        TinFormat format;
        std::function<void(TinWriteOptions&)> ask;
        std::string message;
    };
    const std::vector<Case> cases = {
        {TinFormat::Shapefile, [](TinWriteOptions& o) { o.nodes = true; },
         "{nodes} needs a GeoPackage output (.gpkg), not ESRI Shapefile"},
        {TinFormat::TwoDm, [](TinWriteOptions& o) { o.edges = true; },
         "{edges} needs a GeoPackage output (.gpkg), not 2DM"},
        {TinFormat::FlatGeobuf, [](TinWriteOptions& o) { o.appendLayer = true; },
         "{append_layer} needs a GeoPackage output (.gpkg), not FlatGeobuf"},
        {TinFormat::Ply, [](TinWriteOptions& o) { o.spatialIndex = false; },
         "{no_spatial_index} applies to GeoPackage and FlatGeobuf, not PLY"},
        {TinFormat::Obj, [](TinWriteOptions& o) { o.qgisStyle = true; },
         "{qgis_style} applies to GeoPackage, Shapefile and FlatGeobuf outputs, not OBJ"},
        {TinFormat::GeoPackage,
         [](TinWriteOptions& o) {
             o.qgisStyle = true;
             o.attributes = AttributeSet::None;
         },
         "{qgis_style} colours by z_mean: it needs {attributes} basic or all"},
    };
    for (const Naming& naming : namings()) {
        for (const Case& c : cases) {
            TinWriteOptions options = optionsFor(c.format, naming);
            c.ask(options);
            expectSpelled(refusal([&] { checkTinWriteOptions(options); }, naming.naming), c.message,
                          naming);
        }
    }
}

TEST(WriterMessages, NameTheFormatOptionTheCallersWay_WhenTheExtensionIsUnknown) {
    for (const Naming& naming : namings())
        expectSpelled(refusal([&] { tinFormatFromPath("hood.stl"); }, naming.naming),
                      "use .gpkg .shp .fgb .2dm .ply .obj .xml .landxml (or {format})", naming);
    // Named by no one: the keyword.
    EXPECT_NE(refusal([] { tinFormatFromPath("hood.stl"); }).find("(or format)"),
              std::string::npos);
}

TEST(WriterMessages, NameTheOverwriteOptionTheCallersWay_WhenTheOutputExists) {
    for (const Naming& naming : namings()) {
        const TemporaryDirectory directory;
        std::ofstream(directory / "tin.ply") << "someone's";
        expectSpelled(refusal(
                          [&] {
                              writeTin(test::gridTin(3), directory / "tin.ply",
                                       optionsFor(TinFormat::Ply, naming));
                          },
                          naming.naming),
                      "tin.ply' exists; use {overwrite}", naming);
    }
}

TEST(WriterMessages, NameTheOverwriteOptionTheCallersWay_WhenTheOutputAppearsDuringTheRun) {
    for (const Naming& naming : namings()) {
        const TemporaryDirectory directory;
        const auto output = directory / "tin.obj";
        const auto createTheOutput = [&](double, std::string_view) {
            if (!std::filesystem::exists(output))
                std::ofstream(output) << "someone's";
            return true;
        };
        expectSpelled(refusal(
                          [&] {
                              writeTin(test::gridTin(5), output, optionsFor(TinFormat::Obj, naming),
                                       createTheOutput);
                          },
                          naming.naming),
                      "appeared while this run was writing; it was left as it is (use "
                      "{overwrite} to replace it)",
                      naming);
    }
}

TEST(WriterMessages, NameTheLayerAndOverwriteOptionsTheCallersWay_WhenAnAppendedLayerExists) {
    for (const Naming& naming : namings()) {
        const TemporaryDirectory directory;
        const auto output = directory / "tin.gpkg";
        TinWriteOptions options = optionsFor(TinFormat::GeoPackage, naming);
        writeTin(test::gridTin(3), output, options);
        options.appendLayer = true;
        expectSpelled(refusal([&] { writeTin(test::gridTin(3), output, options); }, naming.naming),
                      "already has a layer 'tin'; choose another {layer} or use {overwrite} to "
                      "replace it",
                      naming);
    }
}

TEST(WriterMessages, RefuseALayerNameThatIsNotUtf8_NamingTheByte) {
    // A GeoPackage table name and a LandXML attribute must be UTF-8: the message names the
    // first byte that starts no UTF-8 character, and nothing is written, whatever the format.
    const std::vector<std::pair<std::string, std::string>> cases = {
        {"caf\xE9", "(0xE9 at byte 4)"},          // Latin-1, as a script may pass it
        {"ab\xE2\x82", "(0xE2 at byte 3)"},       // cut in the middle of a character
        {"\x80xyz", "(0x80 at byte 1)"},          // a continuation byte without its lead
        {"\xC0\xAF", "(0xC0 at byte 1)"},         // an overlong '/'
        {"x\xED\xA0\x80", "(0xED at byte 2)"},    // a UTF-16 surrogate, U+D800
        {"\xF4\x90\x80\x80", "(0xF4 at byte 1)"}, // past U+10FFFF
    };
    for (const auto& [format, extension] :
         std::vector<std::pair<TinFormat, std::string>>{{TinFormat::GeoPackage, ".gpkg"},
                                                        {TinFormat::LandXml, ".xml"},
                                                        {TinFormat::Shapefile, ".shp"},
                                                        {TinFormat::Obj, ".obj"}}) {
        for (const auto& [name, where] : cases) {
            const TemporaryDirectory directory;
            TinWriteOptions options = optionsFor(format, namings().front());
            options.layerName = name;
            const std::string message = refusal(
                [&] { writeTin(test::gridTin(3), directory / ("tin" + extension), options); });
            EXPECT_NE(message.find("the layer name is not valid UTF-8 " + where), std::string::npos)
                << extension << ": " << message;
            EXPECT_EQ(directory.entries(), std::set<std::string>{}) << extension;
        }
    }
    // U+FFFF is UTF-8 but no character, and XML cannot hold it.
    TinWriteOptions options = optionsFor(TinFormat::LandXml, namings().front());
    options.layerName = "a\xEF\xBF\xBF";
    EXPECT_NE(refusal([&] { checkTinWriteOptions(options); }).find("U+FFFF at byte 2"),
              std::string::npos);
    // Characters of two, three and four bytes pass, U+FFFD and U+10FFFF among them.
    for (const std::string name : {"Mt Hood \xE2\x80\x93 1 m", "\xE5\xB1\xB1", "\xF0\x9F\x98\x80",
                                   "\xEF\xBF\xBD", "\xF4\x8F\xBF\xBF", "caf\xC3\xA9"}) {
        options.layerName = name;
        EXPECT_EQ(refusal([&] { checkTinWriteOptions(options); }), "") << name;
    }
}

} // namespace
} // namespace terratin::io

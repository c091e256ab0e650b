// Outputs under hostile conditions: files of the same name that belong to someone else,
// outputs that appear while a run is writing, the longest legal names and outputs that are
// not regular files. Every test checks that what was there before
// is byte-identical afterwards and that no temporary is left.

#include "terratin/io/tin_writer.hpp"

#include "mesh_readers.hpp"
#include "ogr_test_support.hpp"
#include "temporary_directory.hpp"
#include "terratin/error.hpp"

#include <gtest/gtest.h>

#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <unistd.h>

#include <cerrno>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <string>
#include <utility>
#include <vector>

namespace terratin::io {
namespace {

namespace fs = std::filesystem;
using test::fileBytes;
using test::TemporaryDirectory;

TinWriteOptions optionsFor(TinFormat format, bool overwrite = false) {
    TinWriteOptions options;
    options.format = format;
    options.crsWkt = test::utm10nWkt();
    options.overwrite = overwrite;
    return options;
}

/// Every format with the extension it is written under.
const std::vector<std::pair<TinFormat, std::string>>& everyFormat() {
    static const std::vector<std::pair<TinFormat, std::string>> formats = {
        {TinFormat::GeoPackage, ".gpkg"}, {TinFormat::Shapefile, ".shp"},
        {TinFormat::FlatGeobuf, ".fgb"},  {TinFormat::TwoDm, ".2dm"},
        {TinFormat::Ply, ".ply"},         {TinFormat::Obj, ".obj"},
        {TinFormat::LandXml, ".xml"}};
    return formats;
}

void writeText(const fs::path& path, const std::string& text) {
    std::ofstream(path, std::ios::binary) << text;
}

/// The directory's entries and their bytes (empty for anything but a regular file).
std::map<std::string, std::string> snapshot(const TemporaryDirectory& directory) {
    std::map<std::string, std::string> files;
    for (const auto& name : directory.entries()) {
        const fs::path path = directory / name;
        files[name] = fs::is_regular_file(fs::symlink_status(path)) ? fileBytes(path) : "";
    }
    return files;
}

TEST(HostileOutput, D1_ShapefileKeepsForeignPrjAndCpg_WhenNotOverwriting) {
    // An ESRI ASCII grid's own .prj (and any other sidecar of the same base name) is not the
    // Shapefile's to replace: the run must refuse before writing anything.
    for (const std::string sidecar : {".prj", ".cpg", ".qix", ".qml", ".sbn", ".shp.xml", ".PRJ"}) {
        const TemporaryDirectory directory;
        writeText(directory / "grid.asc", "ncols 2\n");
        writeText(directory / ("grid" + sidecar), "the grid's own " + sidecar);
        const auto before = snapshot(directory);
        try {
            writeTin(test::gridTin(3), directory / "grid.shp", optionsFor(TinFormat::Shapefile));
            ADD_FAILURE() << "wrote a Shapefile beside an existing " << sidecar;
        } catch (const InvalidInputError& error) {
            EXPECT_NE(std::string(error.what()).find("grid" + sidecar), std::string::npos)
                << error.what();
        }
        EXPECT_EQ(snapshot(directory), before) << sidecar;
    }
}

TEST(HostileOutput, D1_ShapefileReplacesItsSidecars_WhenOverwriting) {
    const TemporaryDirectory directory;
    writeText(directory / "tin.prj", "old projection");
    writeText(directory / "tin.qix", "old index");
    writeTin(test::gridTin(3), directory / "tin.shp", optionsFor(TinFormat::Shapefile, true));
    EXPECT_EQ(directory.entries(),
              (std::set<std::string>{"tin.shp", "tin.shx", "tin.dbf", "tin.prj", "tin.cpg"}));
    EXPECT_NE(fileBytes(directory / "tin.prj"), "old projection");
}

TEST(HostileOutput, D5_RefusesAnOutputThatAppearsDuringTheRun_ForEveryFormat) {
    // Another program creates the output after the up-front check, while the run is writing:
    // the final rename must leave it as it is and take nothing of the run's into place.
    for (const auto& [format, extension] : everyFormat()) {
        for (const std::string& intruder : format == TinFormat::Shapefile
                                               ? std::vector<std::string>{".shp", ".dbf", ".prj"}
                                               : std::vector<std::string>{extension}) {
            const TemporaryDirectory directory;
            const fs::path output = directory / ("tin" + extension);
            bool created = false;
            const auto createTheOutput = [&](double, std::string_view) {
                if (!created)
                    writeText(directory / ("tin" + intruder), "written by someone else");
                created = true;
                return true;
            };
            try {
                writeTin(test::gridTin(5), output, optionsFor(format), createTheOutput);
                ADD_FAILURE() << "replaced tin" << intruder << " that appeared during the run";
            } catch (const InvalidInputError& error) {
                EXPECT_NE(std::string(error.what()).find("appeared"), std::string::npos)
                    << error.what();
            }
            ASSERT_TRUE(created) << extension;
            EXPECT_EQ(snapshot(directory), (std::map<std::string, std::string>{
                                               {"tin" + intruder, "written by someone else"}}))
                << extension << " with tin" << intruder;
        }
    }
}

TEST(HostileOutput, D5_LeavesASidecarThatAppearsDuringTheRun_WhenNotOverwriting) {
    // A .qix that another program makes while the Shapefile is written is not the run's: the
    // Shapefile goes in beside it, and the .qix stays.
    const TemporaryDirectory directory;
    bool created = false;
    writeTin(test::gridTin(5), directory / "tin.shp", optionsFor(TinFormat::Shapefile),
             [&](double, std::string_view) {
                 if (!created)
                     writeText(directory / "tin.qix", "someone's index");
                 created = true;
                 return true;
             });
    EXPECT_EQ(fileBytes(directory / "tin.qix"), "someone's index");
    EXPECT_TRUE(fs::exists(directory / "tin.shp"));
}

TEST(HostileOutput, D5_ReplacesAnOutputThatAppearsDuringTheRun_WhenOverwriting) {
    for (const auto& [format, extension] : everyFormat()) {
        const TemporaryDirectory directory;
        const fs::path output = directory / ("tin" + extension);
        bool created = false;
        writeTin(test::gridTin(5), output, optionsFor(format, true), [&](double, std::string_view) {
            if (!created)
                writeText(output, "written by someone else");
            created = true;
            return true;
        });
        EXPECT_NE(fileBytes(output), "written by someone else") << extension;
    }
}

TEST(HostileOutput, D5_RefusesAStyleThatAppearsDuringTheRun_AndTakesTheDataBack) {
    const TemporaryDirectory directory;
    TinWriteOptions options = optionsFor(TinFormat::GeoPackage);
    options.qgisStyle = true;
    bool created = false;
    EXPECT_THROW(writeTin(test::gridTin(5), directory / "tin.gpkg", options,
                          [&](double, std::string_view) {
                              if (!created)
                                  writeText(directory / "tin.qml", "someone's style");
                              created = true;
                              return true;
                          }),
                 InvalidInputError);
    EXPECT_EQ(snapshot(directory),
              (std::map<std::string, std::string>{{"tin.qml", "someone's style"}}));
}

TEST(HostileOutput, LeavesNoTemporary_WhenTheOutputDirectoryIsRenamedDuringTheRun) {
    // Someone (a user, a sync tool) renames the output's directory once the run has started
    // writing: the run fails, and its temporaries go from the directory wherever it went. The
    // GeoPackage fails at the final rename, which says why; other formats may fail before, in
    // GDAL, with GDAL's reason.
    for (const auto& [format, extension] : everyFormat()) {
        const TemporaryDirectory root;
        fs::create_directory(root / "out");
        bool moved = false;
        const auto moveTheDirectory = [&](double fraction, std::string_view) {
            if (!moved && fraction > 0.0) { // the temporary exists by then
                fs::rename(root / "out", root / "moved");
                moved = true;
            }
            return true;
        };
        try {
            writeTin(test::gridTin(5), root / "out" / ("tin" + extension), optionsFor(format),
                     moveTheDirectory);
            ADD_FAILURE() << extension << ": written although its directory was moved";
        } catch (const Error& error) {
            if (format == TinFormat::GeoPackage) {
                EXPECT_NE(std::string(error.what()).find("was moved"), std::string::npos)
                    << error.what();
            }
        }
        ASSERT_TRUE(moved) << extension;
        EXPECT_EQ(TemporaryDirectory::entriesOf(root / "moved"), std::set<std::string>{})
            << extension;
        EXPECT_EQ(root.entries(), std::set<std::string>{"moved"}) << extension;
    }
}

TEST(HostileOutput, D17_WritesAnOutputNamedWith255Bytes_ForEveryFormat) {
    // 255 bytes is the longest legal name; the temporary name must not need more.
    for (const auto& [format, extension] : everyFormat()) {
        const TemporaryDirectory directory;
        const std::string name = std::string(255 - extension.size(), 'n') + extension;
        writeTin(test::gridTin(4), directory / name, optionsFor(format));
        EXPECT_TRUE(fs::is_regular_file(directory / name)) << extension;
        for (const auto& entry : directory.entries())
            EXPECT_EQ(entry.find(".tmp-"), std::string::npos) << entry;
    }
}

TEST(HostileOutput, D17_WritesAnOutputWithA250ByteMultibyteName) {
    // The temporary name is cut short at a character boundary: 'é' is two bytes.
    const TemporaryDirectory directory;
    std::string stem;
    while (stem.size() + 2 <= 250 - 5)
        stem += "\xC3\xA9";
    writeTin(test::gridTin(4), directory / (stem + ".gpkg"), optionsFor(TinFormat::GeoPackage));
    EXPECT_EQ(directory.entries(), (std::set<std::string>{stem + ".gpkg"}));
}

TEST(HostileOutput, D18_RefusesFifoAndSymlink_EvenWhenOverwriting) {
    const TemporaryDirectory directory;
    ASSERT_EQ(::mkfifo(directory.file("pipe.gpkg").c_str(), 0600), 0);
    writeText(directory / "target.ply", "the link's target");
    fs::create_symlink("target.ply", directory / "link.ply");
    const auto before = snapshot(directory);

    for (const auto& [name, format, kind] :
         {std::tuple{"pipe.gpkg", TinFormat::GeoPackage, "FIFO"},
          std::tuple{"link.ply", TinFormat::Ply, "symbolic link"}}) {
        try {
            writeTin(test::gridTin(3), directory / name, optionsFor(format, true));
            ADD_FAILURE() << "replaced " << name;
        } catch (const IoError& error) {
            EXPECT_NE(std::string(error.what()).find(kind), std::string::npos) << error.what();
        }
    }
    EXPECT_EQ(snapshot(directory), before);
    EXPECT_TRUE(fs::is_fifo(directory / "pipe.gpkg"));
    EXPECT_TRUE(fs::is_symlink(directory / "link.ply"));
}

TEST(HostileOutput, D18_RefusesACharacterDevice_EvenWhenOverwriting) {
    // A node like /dev/null, made here so that a broken writer could not harm the real one.
    const TemporaryDirectory directory;
    const fs::path device = directory / "null.gpkg";
    if (::mknod(device.c_str(), S_IFCHR | 0666, makedev(1, 3)) != 0)
        GTEST_SKIP() << "cannot make a device node here (errno " << errno << ")";
    try {
        writeTin(test::gridTin(3), device, optionsFor(TinFormat::GeoPackage, true));
        ADD_FAILURE() << "replaced a character device";
    } catch (const IoError& error) {
        EXPECT_NE(std::string(error.what()).find("character device"), std::string::npos)
            << error.what();
    }
    EXPECT_TRUE(fs::is_character_file(fs::symlink_status(device)));
    EXPECT_EQ(directory.entries(), (std::set<std::string>{"null.gpkg"}));
}

TEST(HostileOutput, D18_RefusesASymlinkedGeoPackage_WhenAppendingALayer) {
    const TemporaryDirectory directory;
    writeTin(test::gridTin(3), directory / "real.gpkg", optionsFor(TinFormat::GeoPackage));
    fs::create_symlink("real.gpkg", directory / "link.gpkg");
    const auto before = snapshot(directory);
    TinWriteOptions options = optionsFor(TinFormat::GeoPackage);
    options.appendLayer = true;
    options.layerName = "second";
    EXPECT_THROW(writeTin(test::gridTin(3), directory / "link.gpkg", options), IoError);
    EXPECT_EQ(snapshot(directory), before);
    EXPECT_TRUE(fs::is_symlink(directory / "link.gpkg"));
}

} // namespace
} // namespace terratin::io

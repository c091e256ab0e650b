#include "terratin/io/tin_writer.hpp"

#include "terratin/error.hpp"
#include "terratin/gdal_error.hpp"
#include "terratin/geometry/triangle_attributes.hpp"

#include <gdal_priv.h>
#include <ogr_feature.h>
#include <ogr_geometry.h>
#include <ogr_spatialref.h>
#include <ogrsf_frmts.h>

#include "mesh_readers.hpp"
#include "ogr_test_support.hpp"

#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <set>
#include <string>
#include <tuple>
#include <vector>

namespace terratin::io {
namespace {

namespace fs = std::filesystem;

// DBF columns hold 12 decimals (see tin_writer.cpp); the values read back differ from the
// computed doubles by at most half a unit in the last decimal.
constexpr double kDbfTolerance = 1e-11;

constexpr double kOriginX = 500000.0; // UTM-like, so that large coordinates are exercised
constexpr double kOriginY = 5000000.0;
constexpr double kSpacingM = 10.0;

double terrainZ(double dx, double dy) {
    return 100.0 + 0.1 * dx - 0.2 * dy + 0.001 * dx * dy;
}

/// An n x n grid of vertices at (kOriginX, kOriginY) + kSpacingM steps on the saddle terrainZ.
TinMesh gridMesh(int n) {
    return test::gridTin(n, terrainZ(0.0, 0.0));
}

using test::utm10nWkt;

std::string readBytes(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::string bytes(static_cast<std::size_t>(fs::file_size(path)), '\0');
    in.read(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    return bytes;
}

std::set<std::string> entriesOf(const fs::path& directory) {
    std::set<std::string> names;
    for (const auto& entry : fs::directory_iterator(directory))
        names.insert(entry.path().filename().string());
    return names;
}

/// Twice the signed area of a closed ring: positive when counter-clockwise.
double signedArea2(const OGRLinearRing& ring) {
    double sum = 0.0;
    for (int k = 0; k + 1 < ring.getNumPoints(); ++k)
        sum += ring.getX(k) * ring.getY(k + 1) - ring.getX(k + 1) * ring.getY(k);
    return sum;
}

GDALDatasetUniquePtr openVector(const fs::path& path) {
    initialiseGdal();
    return GDALDatasetUniquePtr(GDALDataset::Open(path.c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY));
}

class OgrTinWriter : public ::testing::Test {
protected:
    void SetUp() override {
        std::random_device device;
        m_directory =
            fs::temp_directory_path() /
            ("terratin-writer-test-" + std::to_string(::getpid()) + "-" + std::to_string(device()));
        fs::create_directories(m_directory);
    }
    void TearDown() override {
        std::error_code error;
        fs::permissions(m_directory, fs::perms::owner_all, fs::perm_options::add, error);
        fs::remove_all(m_directory, error);
    }

    [[nodiscard]] fs::path path(const std::string& name) const { return m_directory / name; }

    static TinWriteOptions optionsFor(TinFormat format, std::string crsWkt = {}) {
        TinWriteOptions options;
        options.format = format;
        options.crsWkt = std::move(crsWkt);
        return options;
    }

    /// Reads every feature back and compares it with the mesh: one Polygon Z per triangle,
    /// in mesh order, a closed 4-point ring whose corners are the triangle's vertices with
    /// exact coordinates, and the attributes of computeTriangleAttributes.
    static void expectTrianglesReadBack(const fs::path& file, const TinMesh& mesh,
                                        bool ringIsCounterClockwise, double attributeTolerance) {
        const auto dataset = openVector(file);
        ASSERT_TRUE(dataset) << file;
        ASSERT_EQ(dataset->GetLayerCount(), 1);
        OGRLayer* layer = dataset->GetLayer(0);
        EXPECT_EQ(layer->GetGeomType(), wkbPolygon25D);
        ASSERT_EQ(layer->GetFeatureCount(), static_cast<GIntBig>(mesh.triangleCount()));

        std::size_t t = 0;
        for (const auto& feature : *layer) {
            ASSERT_LT(t, mesh.triangleCount());
            const OGRGeometry* geometry = feature->GetGeometryRef();
            ASSERT_NE(geometry, nullptr);
            ASSERT_EQ(geometry->getGeometryType(), wkbPolygon25D);
            const auto* polygon = geometry->toPolygon();
            ASSERT_EQ(polygon->getNumInteriorRings(), 0);
            const OGRLinearRing* ring = polygon->getExteriorRing();
            ASSERT_EQ(ring->getNumPoints(), 4);
            EXPECT_TRUE(ring->get_IsClosed());
            EXPECT_EQ(signedArea2(*ring) > 0.0, ringIsCounterClockwise) << "triangle " << t;

            // The mesh's corner order, or its reverse for a clockwise ring, from some start.
            std::vector<Point3> corners;
            for (int k = 0; k < 3; ++k)
                corners.push_back(mesh.vertices[mesh.triangles[3 * t + k]]);
            if (!ringIsCounterClockwise)
                std::reverse(corners.begin(), corners.end());
            const Point3 first{ring->getX(0), ring->getY(0), ring->getZ(0)};
            const auto start = std::find(corners.begin(), corners.end(), first);
            ASSERT_NE(start, corners.end()) << "triangle " << t;
            std::rotate(corners.begin(), start, corners.end());
            for (int k = 0; k < 3; ++k) {
                EXPECT_EQ(ring->getX(k), corners[k].x);
                EXPECT_EQ(ring->getY(k), corners[k].y);
                EXPECT_EQ(ring->getZ(k), corners[k].z);
            }

            const TriangleAttributes expected = computeTriangleAttributes(
                mesh.vertices[mesh.triangles[3 * t]], mesh.vertices[mesh.triangles[3 * t + 1]],
                mesh.vertices[mesh.triangles[3 * t + 2]]);
            EXPECT_NEAR(feature->GetFieldAsDouble("z_min"), expected.zMin, attributeTolerance);
            EXPECT_NEAR(feature->GetFieldAsDouble("z_max"), expected.zMax, attributeTolerance);
            EXPECT_NEAR(feature->GetFieldAsDouble("z_mean"), expected.zMean, attributeTolerance);
            EXPECT_NEAR(feature->GetFieldAsDouble("slope_deg"), expected.slopeDeg,
                        attributeTolerance);
            EXPECT_NEAR(feature->GetFieldAsDouble("aspect_deg"), expected.aspectDeg,
                        attributeTolerance);
            EXPECT_NEAR(feature->GetFieldAsDouble("area_2d"), expected.area2d, attributeTolerance);
            ++t;
        }
        EXPECT_EQ(t, mesh.triangleCount());
    }

    static void expectCrs(const fs::path& file, const std::string& wkt) {
        const auto dataset = openVector(file);
        ASSERT_TRUE(dataset) << file;
        const OGRSpatialReference* srs = dataset->GetLayer(0)->GetSpatialRef();
        if (wkt.empty()) {
            EXPECT_EQ(srs, nullptr);
            return;
        }
        ASSERT_NE(srs, nullptr);
        OGRSpatialReference expected;
        ASSERT_EQ(expected.importFromWkt(wkt.c_str()), OGRERR_NONE);
        EXPECT_TRUE(srs->IsSame(&expected));
    }

    fs::path m_directory;
};

TEST(TinFormat, ParsesShortAndDriverNames_WhenCaseDiffers) {
    EXPECT_EQ(parseTinFormat("GPKG"), TinFormat::GeoPackage);
    EXPECT_EQ(parseTinFormat("gpkg"), TinFormat::GeoPackage);
    EXPECT_EQ(parseTinFormat("GeoPackage"), TinFormat::GeoPackage);
    EXPECT_EQ(parseTinFormat("SHP"), TinFormat::Shapefile);
    EXPECT_EQ(parseTinFormat("shp"), TinFormat::Shapefile);
    EXPECT_EQ(parseTinFormat("ESRI Shapefile"), TinFormat::Shapefile);
}

TEST(TinFormat, ThrowsInvalidInput_WhenNameIsUnknown) {
    EXPECT_THROW(parseTinFormat("GeoJSON"), InvalidInputError);
    EXPECT_THROW(parseTinFormat(""), InvalidInputError);
}

TEST(TinFormat, FollowsExtension_WhenPathIsGpkgOrShp) {
    EXPECT_EQ(tinFormatFromPath("out/tin.gpkg"), TinFormat::GeoPackage);
    EXPECT_EQ(tinFormatFromPath("TIN.GPKG"), TinFormat::GeoPackage);
    EXPECT_EQ(tinFormatFromPath("/data/tin.shp"), TinFormat::Shapefile);
    EXPECT_EQ(tinFormatFromPath("tin.SHP"), TinFormat::Shapefile);
    EXPECT_THROW(tinFormatFromPath("tin.geojson"), InvalidInputError);
    EXPECT_THROW(tinFormatFromPath("tin"), InvalidInputError);
}

TEST(TinMeshFixture, GridMeshIsConsistent_WhenBuiltByTheTests) {
    // The writer tests rely on this hand-built mesh: check it obeys the TinMesh contract.
    const TinMesh mesh = gridMesh(4);
    ASSERT_EQ(mesh.triangleCount(), 18u);
    for (std::size_t t = 0; t < mesh.triangleCount(); ++t) {
        const Point3& a = mesh.vertices[mesh.triangles[3 * t]];
        const Point3& b = mesh.vertices[mesh.triangles[3 * t + 1]];
        const Point3& c = mesh.vertices[mesh.triangles[3 * t + 2]];
        EXPECT_GT((b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x), 0.0);
        for (int e = 0; e < 3; ++e) {
            const std::int32_t other = mesh.neighbours[3 * t + e];
            if (other == kNoNeighbour)
                continue;
            const std::uint32_t from = mesh.triangles[3 * t + e];
            const std::uint32_t to = mesh.triangles[3 * t + (e + 1) % 3];
            bool twin = false;
            for (int f = 0; f < 3; ++f) {
                const auto o = static_cast<std::size_t>(other);
                twin = twin || (mesh.triangles[3 * o + f] == to &&
                                mesh.triangles[3 * o + (f + 1) % 3] == from &&
                                mesh.neighbours[3 * o + f] == static_cast<std::int32_t>(t));
            }
            EXPECT_TRUE(twin) << "triangle " << t << " edge " << e;
        }
    }
}

TEST_F(OgrTinWriter, WritesOneCcwPolygonZPerTriangle_WhenGeoPackage) {
    const TinMesh mesh = gridMesh(3);
    const fs::path output = path("tin.gpkg");
    writeTin(mesh, output, optionsFor(TinFormat::GeoPackage));
    // GeoPackage stores doubles: attributes come back bit for bit.
    expectTrianglesReadBack(output, mesh, /*ringIsCounterClockwise=*/true, 0.0);
}

TEST_F(OgrTinWriter, WritesOnePolygonZPerTriangle_WhenShapefile) {
    const TinMesh mesh = gridMesh(3);
    const fs::path output = path("tin.shp");
    writeTin(mesh, output, optionsFor(TinFormat::Shapefile));
    // The Shapefile specification stores outer rings clockwise; GDAL reverses ours to obey.
    expectTrianglesReadBack(output, mesh, /*ringIsCounterClockwise=*/false, kDbfTolerance);
}

TEST_F(OgrTinWriter, NamesTheLayer_WhenGeoPackageLayerNameIsGiven) {
    TinWriteOptions options = optionsFor(TinFormat::GeoPackage);
    options.layerName = "triangles";
    writeTin(gridMesh(3), path("tin.gpkg"), options);
    const auto dataset = openVector(path("tin.gpkg"));
    ASSERT_TRUE(dataset);
    EXPECT_NE(dataset->GetLayerByName("triangles"), nullptr);
}

TEST_F(OgrTinWriter, WritesAspectMinusOne_WhenTriangleIsFlat) {
    TinMesh mesh;
    mesh.vertices = {{0.0, 0.0, 5.0}, {10.0, 0.0, 5.0}, {0.0, 10.0, 5.0}};
    mesh.sourceIndex = {0, 1, 2};
    mesh.triangles = {0, 1, 2};
    mesh.neighbours = {kNoNeighbour, kNoNeighbour, kNoNeighbour};
    for (const auto& [format, name] : {std::pair{TinFormat::GeoPackage, "flat.gpkg"},
                                       std::pair{TinFormat::Shapefile, "flat.shp"}}) {
        writeTin(mesh, path(name), optionsFor(format));
        const auto dataset = openVector(path(name));
        ASSERT_TRUE(dataset);
        OGRFeatureUniquePtr feature(dataset->GetLayer(0)->GetNextFeature());
        ASSERT_TRUE(feature);
        EXPECT_EQ(feature->GetFieldAsDouble("aspect_deg"), -1.0) << name;
        EXPECT_EQ(feature->GetFieldAsDouble("slope_deg"), 0.0) << name;
        EXPECT_EQ(feature->GetFieldAsDouble("area_2d"), 50.0) << name;
    }
}

TEST_F(OgrTinWriter, WritesCrs_WhenGeoPackageHasCrsWkt) {
    const std::string wkt = utm10nWkt();
    writeTin(gridMesh(3), path("tin.gpkg"), optionsFor(TinFormat::GeoPackage, wkt));
    expectCrs(path("tin.gpkg"), wkt);
}

TEST_F(OgrTinWriter, WritesPrjAndCpg_WhenShapefileHasCrsWkt) {
    const std::string wkt = utm10nWkt();
    writeTin(gridMesh(3), path("tin.shp"), optionsFor(TinFormat::Shapefile, wkt));
    EXPECT_TRUE(fs::exists(path("tin.prj")));
    EXPECT_TRUE(fs::exists(path("tin.cpg")));
    expectCrs(path("tin.shp"), wkt);
}

TEST_F(OgrTinWriter, WritesUndefinedCartesianCrs_WhenGeoPackageCrsWktIsEmpty) {
    // Regression: GDAL 3.6 files a layer without CRS as "Undefined geographic SRS", which
    // would declare eastings and northings to be degrees.
    writeTin(gridMesh(3), path("tin.gpkg"), optionsFor(TinFormat::GeoPackage));
    const auto dataset = openVector(path("tin.gpkg"));
    ASSERT_TRUE(dataset);
    const OGRSpatialReference* srs = dataset->GetLayer(0)->GetSpatialRef();
    if (srs != nullptr) {
        EXPECT_FALSE(srs->IsGeographic());
        EXPECT_TRUE(srs->IsLocal());
        EXPECT_STREQ(srs->GetName(), "Undefined Cartesian SRS");
    }
}

TEST_F(OgrTinWriter, WritesNoPrj_WhenShapefileCrsWktIsEmpty) {
    writeTin(gridMesh(3), path("tin.shp"), optionsFor(TinFormat::Shapefile));
    EXPECT_FALSE(fs::exists(path("tin.prj")));
    expectCrs(path("tin.shp"), "");
}

TEST_F(OgrTinWriter, ThrowsCrsError_WhenCrsWktIsInvalid) {
    EXPECT_THROW(writeTin(gridMesh(3), path("tin.gpkg"),
                          optionsFor(TinFormat::GeoPackage, "PROJCS[\"broken\"")),
                 CrsError);
    EXPECT_TRUE(entriesOf(m_directory).empty());
}

TEST_F(OgrTinWriter, LeavesOnlyTheOutput_WhenWriteSucceeds) {
    writeTin(gridMesh(3), path("tin.gpkg"), optionsFor(TinFormat::GeoPackage, utm10nWkt()));
    EXPECT_EQ(entriesOf(m_directory), (std::set<std::string>{"tin.gpkg"}));

    writeTin(gridMesh(3), path("tin.shp"), optionsFor(TinFormat::Shapefile, utm10nWkt()));
    EXPECT_EQ(entriesOf(m_directory), (std::set<std::string>{"tin.gpkg", "tin.shp", "tin.shx",
                                                             "tin.dbf", "tin.prj", "tin.cpg"}));
}

TEST_F(OgrTinWriter,
       ThrowsInvalidInputAndKeepsOutputByteIdentical_WhenOutputExistsWithoutOverwrite) {
    for (const auto& [format, name] : {std::pair{TinFormat::GeoPackage, "tin.gpkg"},
                                       std::pair{TinFormat::Shapefile, "tin.shp"}}) {
        writeTin(gridMesh(3), path(name), optionsFor(format));
        const auto before = entriesOf(m_directory);
        std::map<std::string, std::string> bytes;
        for (const auto& entry : before)
            bytes[entry] = readBytes(path(entry));

        try {
            writeTin(gridMesh(5), path(name), optionsFor(format));
            FAIL() << "an existing " << name << " was overwritten without overwrite";
        } catch (const InvalidInputError& error) {
            // A library caller is pointed to the option by its keyword, not by a command-line flag.
            EXPECT_NE(std::string(error.what()).find("exists; use overwrite"), std::string::npos)
                << error.what();
            EXPECT_EQ(std::string(error.what()).rfind("OgrTinWriter: ", 0), 0u);
        }
        EXPECT_EQ(entriesOf(m_directory), before);
        for (const auto& [entry, content] : bytes)
            EXPECT_EQ(readBytes(path(entry)), content) << entry;
    }
}

TEST_F(OgrTinWriter, ThrowsInvalidInput_WhenOnlyTheShapefileDbfExists) {
    std::ofstream(path("tin.dbf")) << "not really a dbf";
    EXPECT_THROW(writeTin(gridMesh(3), path("tin.shp"), optionsFor(TinFormat::Shapefile)),
                 InvalidInputError);
    EXPECT_EQ(readBytes(path("tin.dbf")), "not really a dbf");
}

TEST_F(OgrTinWriter, ReplacesOutput_WhenGeoPackageExistsWithOverwrite) {
    writeTin(gridMesh(3), path("tin.gpkg"), optionsFor(TinFormat::GeoPackage));
    TinWriteOptions options = optionsFor(TinFormat::GeoPackage);
    options.overwrite = true;
    const TinMesh larger = gridMesh(5);
    writeTin(larger, path("tin.gpkg"), options);
    expectTrianglesReadBack(path("tin.gpkg"), larger, true, 0.0);
    EXPECT_EQ(entriesOf(m_directory), (std::set<std::string>{"tin.gpkg"}));
}

TEST_F(OgrTinWriter, ReplacesOutputAndRemovesStaleSidecars_WhenShapefileExistsWithOverwrite) {
    writeTin(gridMesh(3), path("tin.shp"), optionsFor(TinFormat::Shapefile, utm10nWkt()));
    std::ofstream(path("tin.qix")) << "stale spatial index of the old geometry";
    std::ofstream(path("other.qix")) << "belongs to another data set";

    TinWriteOptions options = optionsFor(TinFormat::Shapefile); // no CRS: the old .prj is stale
    options.overwrite = true;
    const TinMesh larger = gridMesh(5);
    writeTin(larger, path("tin.shp"), options);

    expectTrianglesReadBack(path("tin.shp"), larger, false, kDbfTolerance);
    expectCrs(path("tin.shp"), "");
    EXPECT_EQ(entriesOf(m_directory),
              (std::set<std::string>{"tin.shp", "tin.shx", "tin.dbf", "tin.cpg", "other.qix"}));
}

TEST_F(OgrTinWriter, NamesComponentsInUpperCase_WhenShapefileExtensionIsUpperCase) {
    writeTin(gridMesh(3), path("TIN.SHP"), optionsFor(TinFormat::Shapefile, utm10nWkt()));
    EXPECT_EQ(entriesOf(m_directory),
              (std::set<std::string>{"TIN.SHP", "TIN.SHX", "TIN.DBF", "TIN.PRJ", "TIN.CPG"}));
    expectTrianglesReadBack(path("TIN.SHP"), gridMesh(3), false, kDbfTolerance);
}

TEST_F(OgrTinWriter, KeepsOldOutputAndLeavesNoTemporaries_WhenCancelledAtStart) {
    for (const auto& [format, name] : {std::pair{TinFormat::GeoPackage, "tin.gpkg"},
                                       std::pair{TinFormat::Shapefile, "tin.shp"}}) {
        writeTin(gridMesh(3), path(name), optionsFor(format));
        const auto before = entriesOf(m_directory);
        const std::string oldBytes = readBytes(path(name));

        TinWriteOptions options = optionsFor(format);
        options.overwrite = true;
        EXPECT_THROW(writeTin(gridMesh(5), path(name), options,
                              [](double, std::string_view) { return false; }),
                     Cancelled);
        EXPECT_EQ(entriesOf(m_directory), before);
        EXPECT_EQ(readBytes(path(name)), oldBytes);
    }
}

TEST_F(OgrTinWriter, KeepsOldOutputAndLeavesNoTemporaries_WhenCancelledMidWrite) {
    // 2 * 199^2 = 79202 triangles: the progress callback fires again after 65536 of them, while
    // the temporary file is open and (for GeoPackage) a transaction is in progress.
    const TinMesh mesh = gridMesh(200);
    for (const auto& [format, name] : {std::pair{TinFormat::GeoPackage, "tin.gpkg"},
                                       std::pair{TinFormat::Shapefile, "tin.shp"}}) {
        writeTin(gridMesh(3), path(name), optionsFor(format));
        const auto before = entriesOf(m_directory);
        const std::string oldBytes = readBytes(path(name));

        TinWriteOptions options = optionsFor(format);
        options.overwrite = true;
        bool sawTemporaries = false;
        double lastFraction = -1.0;
        const auto cancelAfterFirstBatch = [&](double fraction, std::string_view) {
            lastFraction = fraction;
            sawTemporaries = sawTemporaries || entriesOf(m_directory).size() > before.size();
            return fraction == 0.0;
        };
        EXPECT_THROW(writeTin(mesh, path(name), options, cancelAfterFirstBatch), Cancelled);
        EXPECT_GT(lastFraction, 0.0);
        EXPECT_TRUE(sawTemporaries) << "the test did not cancel while writing";
        EXPECT_EQ(entriesOf(m_directory), before);
        EXPECT_EQ(readBytes(path(name)), oldBytes);
    }
}

TEST_F(OgrTinWriter, KeepsOldOutputAndLeavesNoTemporaries_WhenCancelledBeforeFinishing) {
    // The last report before the spatial index / closing comes after every triangle has been
    // inserted; a cancel there must still discard them all.
    for (const auto& [format, name] : {std::pair{TinFormat::GeoPackage, "tin.gpkg"},
                                       std::pair{TinFormat::Shapefile, "tin.shp"}}) {
        writeTin(gridMesh(3), path(name), optionsFor(format));
        const auto before = entriesOf(m_directory);
        const std::string oldBytes = readBytes(path(name));

        TinWriteOptions options = optionsFor(format);
        options.overwrite = true;
        std::string lastMessage;
        const auto cancelWhenFinishing = [&](double, std::string_view message) {
            lastMessage = message;
            return message == "Writing triangles";
        };
        EXPECT_THROW(writeTin(gridMesh(20), path(name), options, cancelWhenFinishing), Cancelled);
        EXPECT_NE(lastMessage, "Writing triangles");
        EXPECT_EQ(entriesOf(m_directory), before);
        EXPECT_EQ(readBytes(path(name)), oldBytes);
    }
}

TEST_F(OgrTinWriter, ReportsIncreasingProgressEndingAtOne_WhenWriting) {
    // 79202 Shapefile triangles: a report at the start, one after 65536 features, one before
    // closing, and the final 1. A small GeoPackage: start, spatial index, 1.
    for (const auto& [format, name, mesh] :
         {std::tuple{TinFormat::Shapefile, "tin.shp", gridMesh(200)},
          std::tuple{TinFormat::GeoPackage, "tin.gpkg", gridMesh(3)}}) {
        std::vector<double> fractions;
        writeTin(mesh, path(name), optionsFor(format),
                 [&](double fraction, std::string_view message) {
                     EXPECT_FALSE(message.empty());
                     fractions.push_back(fraction);
                     return true;
                 });
        ASSERT_GE(fractions.size(), 3u) << name;
        EXPECT_EQ(fractions.front(), 0.0) << name;
        EXPECT_EQ(fractions.back(), 1.0) << name;
        EXPECT_TRUE(std::is_sorted(fractions.begin(), fractions.end())) << name;
        EXPECT_TRUE(std::all_of(fractions.begin(), fractions.end(),
                                [](double f) { return f >= 0.0 && f <= 1.0; }));
    }
}

TEST_F(OgrTinWriter, ThrowsIoError_WhenOutputDirectoryDoesNotExist) {
    try {
        writeTin(gridMesh(3), path("missing/tin.gpkg"), optionsFor(TinFormat::GeoPackage));
        FAIL() << "no error";
    } catch (const IoError& error) {
        EXPECT_NE(std::string(error.what()).find("does not exist"), std::string::npos);
    }
    EXPECT_FALSE(fs::exists(path("missing")));
}

TEST_F(OgrTinWriter, ThrowsIoError_WhenOutputParentIsAFile) {
    std::ofstream(path("plain")) << "x";
    EXPECT_THROW(writeTin(gridMesh(3), path("plain/tin.shp"), optionsFor(TinFormat::Shapefile)),
                 IoError);
}

TEST_F(OgrTinWriter, ThrowsIoError_WhenOutputIsADirectory) {
    fs::create_directory(path("tin.gpkg"));
    TinWriteOptions options = optionsFor(TinFormat::GeoPackage);
    options.overwrite = true;
    EXPECT_THROW(writeTin(gridMesh(3), path("tin.gpkg"), options), IoError);
    EXPECT_TRUE(fs::is_directory(path("tin.gpkg")));
}

TEST_F(OgrTinWriter, ThrowsIoError_WhenOutputDirectoryIsNotWritable) {
    const fs::path readOnly = path("read-only");
    fs::create_directory(readOnly);
    fs::permissions(readOnly, fs::perms::owner_read | fs::perms::owner_exec);
    // root (as in many containers) writes through permissions: the check cannot be seen then.
    if (::access(readOnly.c_str(), W_OK) == 0)
        GTEST_SKIP() << "this user can write to a read-only directory";
    for (const auto& [format, name] : {std::pair{TinFormat::GeoPackage, "tin.gpkg"},
                                       std::pair{TinFormat::Shapefile, "tin.shp"}}) {
        try {
            writeTin(gridMesh(3), readOnly / name, optionsFor(format));
            FAIL() << "no error for " << name;
        } catch (const IoError& error) {
            EXPECT_NE(std::string(error.what()).find("not writable"), std::string::npos);
        }
    }
}

TEST_F(OgrTinWriter, ThrowsInvalidInputAndWritesNothing_WhenMeshHasNoTriangles) {
    TinMesh mesh = gridMesh(3);
    mesh.triangles.clear();
    mesh.neighbours.clear();
    EXPECT_THROW(writeTin(mesh, path("tin.gpkg"), optionsFor(TinFormat::GeoPackage)),
                 InvalidInputError);
    EXPECT_THROW(writeTin(mesh, path("tin.shp"), optionsFor(TinFormat::Shapefile)),
                 InvalidInputError);
    EXPECT_TRUE(entriesOf(m_directory).empty());
}

TEST_F(OgrTinWriter, ThrowsInvalidInputAndWritesNothing_WhenTriangleRefersToMissingVertex) {
    TinMesh mesh = gridMesh(3);
    mesh.triangles[4] = static_cast<std::uint32_t>(mesh.vertexCount());
    EXPECT_THROW(writeTin(mesh, path("tin.gpkg"), optionsFor(TinFormat::GeoPackage)),
                 InvalidInputError);
    EXPECT_TRUE(entriesOf(m_directory).empty());
}

TEST_F(OgrTinWriter, ThrowsInvalidInputAndWritesNothing_WhenShapefileWouldExceed2GB) {
    // 13 M triangles * 168 bytes per PolygonZ record > 2 GB. All triangles repeat one vertex:
    // the size check must refuse the mesh before anything else looks at it.
    TinMesh mesh;
    mesh.vertices = {{0.0, 0.0, 0.0}};
    mesh.sourceIndex = {0};
    mesh.triangles.assign(3 * std::size_t{13'000'000}, 0);
    try {
        writeTin(mesh, path("big.shp"), optionsFor(TinFormat::Shapefile));
        FAIL() << "no error";
    } catch (const InvalidInputError& error) {
        EXPECT_NE(std::string(error.what()).find("GeoPackage"), std::string::npos);
    }
    EXPECT_TRUE(entriesOf(m_directory).empty());
}

TEST_F(OgrTinWriter, ThrowsInvalidInput_WhenShapefileOutputDoesNotEndInShp) {
    EXPECT_THROW(writeTin(gridMesh(3), path("tin.dat"), optionsFor(TinFormat::Shapefile)),
                 InvalidInputError);
    EXPECT_TRUE(entriesOf(m_directory).empty());
}

TEST_F(OgrTinWriter, ThrowsInvalidInputAndLeavesNoTemporaries_WhenValueDoesNotFitDbf) {
    TinMesh mesh = gridMesh(3);
    mesh.vertices[4].z = 3e22; // a z_max whose integer part overflows the 24-character column
    EXPECT_THROW(writeTin(mesh, path("tin.shp"), optionsFor(TinFormat::Shapefile)),
                 InvalidInputError);
    EXPECT_TRUE(entriesOf(m_directory).empty());
    // GeoPackage stores doubles and has no such limit.
    writeTin(mesh, path("tin.gpkg"), optionsFor(TinFormat::GeoPackage));
    expectTrianglesReadBack(path("tin.gpkg"), mesh, true, 0.0);
}

TEST_F(OgrTinWriter, KeepsValue_WhenShapefileValueHasMoreDigitsThanTheDbfDecimalsAllow) {
    // 1234567890123.456 needs 13 integer digits: only 10 decimals fit the 24 characters, and
    // they still hold every digit the double has.
    TinMesh mesh;
    mesh.vertices = {{0.0, 0.0, 1234567890123.456}, {10.0, 0.0, 1.0}, {0.0, 10.0, -2.5}};
    mesh.sourceIndex = {0, 1, 2};
    mesh.triangles = {0, 1, 2};
    mesh.neighbours = {kNoNeighbour, kNoNeighbour, kNoNeighbour};
    writeTin(mesh, path("tin.shp"), optionsFor(TinFormat::Shapefile));
    const auto dataset = openVector(path("tin.shp"));
    ASSERT_TRUE(dataset);
    OGRFeatureUniquePtr feature(dataset->GetLayer(0)->GetNextFeature());
    ASSERT_TRUE(feature);
    EXPECT_EQ(feature->GetFieldAsDouble("z_max"), 1234567890123.456);
    EXPECT_EQ(feature->GetFieldAsDouble("z_min"), -2.5);
}

TEST_F(OgrTinWriter, SpatialIndexFindsEveryTriangle_WhenLayerHasOver100kTriangles) {
    // 2 * 250^2 = 125000 triangles: enough for GDAL versions that build the R-tree in a
    // background thread (it waits for 100k envelopes) to do so inside our transaction, the
    // combination that made that build skip features in OSGeo/gdal#6911.
    const TinMesh mesh = gridMesh(251);
    writeTin(mesh, path("tin.gpkg"), optionsFor(TinFormat::GeoPackage));
    EXPECT_EQ(entriesOf(m_directory), (std::set<std::string>{"tin.gpkg"}));

    const auto dataset = openVector(path("tin.gpkg"));
    ASSERT_TRUE(dataset);
    OGRLayer* layer = dataset->GetLayer(0);
    ASSERT_EQ(layer->GetFeatureCount(), static_cast<GIntBig>(mesh.triangleCount()));
    EXPECT_TRUE(layer->TestCapability(OLCFastSpatialFilter)) << "no spatial index";

    // The R-tree preselects features for a spatial filter: a triangle missing from it would
    // be missing from the filtered read. Compare with a brute-force test of every triangle.
    struct Window {
        double minX, minY, maxX, maxY;
    };
    for (const Window& w : {Window{0.5, 0.5, 2499.5, 2499.5}, Window{5.5, 5.5, 24.5, 14.5},
                            Window{1800.5, 2000.5, 2499.5, 2499.5}}) {
        OGRLinearRing windowRing;
        windowRing.addPoint(kOriginX + w.minX, kOriginY + w.minY);
        windowRing.addPoint(kOriginX + w.maxX, kOriginY + w.minY);
        windowRing.addPoint(kOriginX + w.maxX, kOriginY + w.maxY);
        windowRing.addPoint(kOriginX + w.minX, kOriginY + w.maxY);
        windowRing.closeRings();
        OGRPolygon window;
        window.addRing(&windowRing);
        OGREnvelope windowEnvelope;
        window.getEnvelope(&windowEnvelope);

        GIntBig expected = 0;
        for (const auto& feature : *layer) {
            OGREnvelope envelope;
            feature->GetGeometryRef()->getEnvelope(&envelope);
            if (envelope.Intersects(windowEnvelope) &&
                feature->GetGeometryRef()->Intersects(&window))
                ++expected;
        }
        ASSERT_GT(expected, 0);

        layer->SetSpatialFilter(&window);
        GIntBig found = 0;
        for (const auto& feature : *layer)
            found += feature ? 1 : 0;
        layer->SetSpatialFilter(nullptr);
        EXPECT_EQ(found, expected);
    }
}

} // namespace
} // namespace terratin::io

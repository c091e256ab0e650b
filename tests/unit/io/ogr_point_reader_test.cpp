// Tests of OgrPointReader and of the input dispatch (detectInputKind / readInput): point layers
// written here with OGR (GeoPackage) or as text (GeoJSON, CSV with WKT), read back exactly.

#include "terratin/crs/reprojection.hpp"
#include "terratin/error.hpp"
#include "terratin/gdal_error.hpp"
#include "terratin/io/input_reader.hpp"
#include "terratin/io/ogr_point_reader.hpp"

#include <gdal_priv.h>
#include <ogrsf_frmts.h>

#include "temporary_directory.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <string_view>

namespace terratin::io {
namespace {

namespace fs = std::filesystem;
using TempDir = test::TemporaryDirectory;

const std::vector<Point3> kPoints{
    {500000.5, 4900000.25, 101.5}, {500010.0, 4900000.0, 99.0}, {500005.0, 4900010.0, 120.75}};

/// A GeoPackage with a Point Z layer "spots" (EPSG:32619, field "elev" = z + 1000) and a
/// polygon layer "area" before it.
void writeGeoPackage(const std::string& path) {
    initialiseGdal();
    GDALDriver* driver = GetGDALDriverManager()->GetDriverByName("GPKG");
    ASSERT_NE(driver, nullptr);
    std::unique_ptr<GDALDataset> dataset(
        driver->Create(path.c_str(), 0, 0, 0, GDT_Unknown, nullptr));
    ASSERT_NE(dataset, nullptr);
    OGRSpatialReference srs;
    srs.importFromEPSG(32619);
    OGRLayer* area = dataset->CreateLayer("area", &srs, wkbPolygon, nullptr);
    ASSERT_NE(area, nullptr);
    OGRLayer* layer = dataset->CreateLayer("spots", &srs, wkbPoint25D, nullptr);
    ASSERT_NE(layer, nullptr);
    OGRFieldDefn field("elev", OFTReal);
    ASSERT_EQ(layer->CreateField(&field), OGRERR_NONE);
    for (const Point3& p : kPoints) {
        OGRFeature feature(layer->GetLayerDefn());
        OGRPoint point(p.x, p.y, p.z);
        feature.SetGeometry(&point);
        feature.SetField("elev", p.z + 1000.0);
        ASSERT_EQ(layer->CreateFeature(&feature), OGRERR_NONE);
    }
    OGRFeature empty(layer->GetLayerDefn()); // no geometry: filtered out
    ASSERT_EQ(layer->CreateFeature(&empty), OGRERR_NONE);
}

TEST(OgrPointReader, ReadsGeoPackagePointsWithZ_FromTheFirstPointLayer) {
    TempDir dir;
    const std::string path = dir.file("spots.gpkg");
    writeGeoPackage(path);
    const PointCloud cloud = readOgrPoints(path);
    EXPECT_EQ(cloud.kind, InputKind::Vector);
    EXPECT_EQ(cloud.points, kPoints);
    EXPECT_EQ(cloud.recordsRead, 4U);
    EXPECT_EQ(cloud.filteredOut, 1U);
    EXPECT_EQ(crs::describeCrs(cloud.crsWkt).code, "EPSG:32619");

    OgrPointReadOptions byField;
    byField.zField = "elev";
    byField.layer = "spots";
    const PointCloud fromField = readOgrPoints(path, byField);
    ASSERT_EQ(fromField.points.size(), 3U);
    for (std::size_t i = 0; i < 3; ++i)
        EXPECT_EQ(fromField.points[i].z, kPoints[i].z + 1000.0);
}

TEST(OgrPointReader, ThrowsInvalidInput_ForMissingLayerOrField) {
    TempDir dir;
    const std::string path = dir.file("spots.gpkg");
    writeGeoPackage(path);
    OgrPointReadOptions noLayer;
    noLayer.layer = "nothing";
    EXPECT_THROW(readOgrPoints(path, noLayer), InvalidInputError);
    OgrPointReadOptions noField;
    noField.zField = "height";
    try {
        readOgrPoints(path, noField);
        FAIL() << "a missing field was accepted";
    } catch (const InvalidInputError& error) {
        EXPECT_NE(std::string(error.what()).find("elev"), std::string::npos) << error.what();
    }
    OgrPointReadOptions polygons;
    polygons.layer = "area";
    EXPECT_THROW(readOgrPoints(path, polygons), InvalidInputError);
}

TEST(OgrPointReader, ReadsGeoJsonPoints_WithZFromAField) {
    TempDir dir;
    const std::string path = dir.file("spots.geojson");
    std::ofstream(path) << R"({"type": "FeatureCollection", "features": [
      {"type": "Feature", "properties": {"h": 12.5}, "geometry": {"type": "Point", "coordinates": [-71.5, 44.25]}},
      {"type": "Feature", "properties": {"h": null}, "geometry": {"type": "Point", "coordinates": [-71.4, 44.25]}},
      {"type": "Feature", "properties": {"h": 7}, "geometry": {"type": "MultiPoint", "coordinates": [[-71.3, 44.2], [-71.2, 44.1]]}},
      {"type": "Feature", "properties": {"h": 1}, "geometry": {"type": "LineString", "coordinates": [[0, 0], [1, 1]]}}
    ]})";
    OgrPointReadOptions options;
    options.zField = "h";
    const PointCloud cloud = readOgrPoints(path, options);
    EXPECT_EQ(cloud.points,
              (std::vector<Point3>{{-71.5, 44.25, 12.5}, {-71.3, 44.2, 7}, {-71.2, 44.1, 7}}));
    EXPECT_EQ(cloud.recordsRead, 4U);
    EXPECT_EQ(cloud.filteredOut, 2U); // null z, line
    EXPECT_TRUE(crs::describeCrs(cloud.crsWkt).geographic);

    // 2D points without a z field: a clear error, naming the option by its keyword for a
    // library caller and as the caller names it otherwise (the pipeline: --z-field
    // for the command line).
    try {
        readOgrPoints(path);
        FAIL() << "2D points without a z field were accepted";
    } catch (const InvalidInputError& error) {
        EXPECT_NE(std::string(error.what()).find("with z_field"), std::string::npos)
            << error.what();
        EXPECT_EQ(std::string(error.what()).find("--"), std::string::npos) << error.what();
    }
    try {
        readOgrPoints(path);
        FAIL() << "2D points without a z field were accepted";
    } catch (InvalidInputError& error) {
        EXPECT_EQ(error.options(), std::vector<std::string>{"z_field"});
        error.nameOptions(
            [](std::string_view keyword) { return "<" + std::string(keyword) + ">"; });
        EXPECT_NE(std::string(error.what()).find("with <z_field>"), std::string::npos)
            << error.what();
    }
}

TEST(InputReader, DetectsEachKind) {
    TempDir dir;
    writeGeoPackage(dir.file("spots.gpkg"));
    std::ofstream(dir.file("points.xyz")) << "1 2 3\n";
    std::ofstream(dir.file("points.csv")) << "x,y,z\n1,2,3\n";
    std::ofstream(dir.file("wkt.csv")) << "WKT,elev\n\"POINT Z (1 2 3)\",3\n";
    std::ofstream(dir.file("noext")) << "1 2 3\n4 5 6\n";
    std::ofstream(dir.file("cloud.bin")) << "LASF";
    EXPECT_EQ(detectInputKind(dir.file("spots.gpkg")), InputKind::Vector);
    EXPECT_EQ(detectInputKind(dir.file("points.xyz")), InputKind::Text);
    EXPECT_EQ(detectInputKind(dir.file("points.csv")), InputKind::Text);
    EXPECT_EQ(detectInputKind(dir.file("wkt.csv")), InputKind::Vector);
    EXPECT_EQ(detectInputKind(dir.file("noext")), InputKind::Text);
    EXPECT_EQ(detectInputKind(dir.file("cloud.bin")), InputKind::Las);
    EXPECT_EQ(detectInputKind(std::string(TERRATIN_SAMPLE_DEMS) + "/ridges_utm.tif"),
              InputKind::Raster);
    EXPECT_THROW(detectInputKind(dir.file("missing.tif")), IoError);

    const PointCloud csv = readInput(dir.file("wkt.csv"));
    EXPECT_EQ(csv.points, (std::vector<Point3>{{1, 2, 3}}));
}

TEST(InputReader, ReadsRasterWithCellIndex_AndTextWithSidecarPrj) {
    TempDir dir;
    const PointCloud raster = readInput(std::string(TERRATIN_SAMPLE_DEMS) + "/ridges_utm.tif");
    EXPECT_EQ(raster.kind, InputKind::Raster);
    EXPECT_EQ(raster.recordsRead, 320U * 240U);
    EXPECT_EQ(raster.cellIndex.size(), raster.points.size());
    EXPECT_EQ(raster.points.size() + raster.skippedCells, raster.recordsRead);

    std::ofstream(dir.file("pts.txt")) << "1 2 3\n";
    EXPECT_TRUE(readInput(dir.file("pts.txt")).crsWkt.empty());
    std::ofstream(dir.file("pts.prj")) << crs::crsFromUserInput("EPSG:3358", "test");
    EXPECT_EQ(crs::describeCrs(readInput(dir.file("pts.txt")).crsWkt).code, "EPSG:3358");
}

} // namespace
} // namespace terratin::io

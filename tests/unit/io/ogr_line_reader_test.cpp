// Tests of OgrLineReader: line layers written here with OGR (GeoPackage), read back exactly.

#include "terratin/error.hpp"
#include "terratin/gdal_error.hpp"
#include "terratin/io/ogr_line_reader.hpp"

#include <gdal_priv.h>
#include <ogrsf_frmts.h>

#include "temporary_directory.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <string>
#include <vector>

namespace terratin::io {
namespace {

using TempDir = test::TemporaryDirectory;

/// A GeoPackage whose layers each hold the features of `wkts` (one layer per entry).
void writeLayers(const std::string& path,
                 const std::vector<std::pair<std::string, std::vector<std::string>>>& layers) {
    initialiseGdal();
    GDALDriver* driver = GetGDALDriverManager()->GetDriverByName("GPKG");
    ASSERT_NE(driver, nullptr);
    std::unique_ptr<GDALDataset> dataset(
        driver->Create(path.c_str(), 0, 0, 0, GDT_Unknown, nullptr));
    ASSERT_NE(dataset, nullptr);
    OGRSpatialReference srs;
    srs.importFromEPSG(32633);
    for (const auto& [name, wkts] : layers) {
        OGRLayer* layer = dataset->CreateLayer(name.c_str(), &srs, wkbUnknown, nullptr);
        ASSERT_NE(layer, nullptr);
        for (const std::string& wkt : wkts) {
            OGRFeature feature(layer->GetLayerDefn());
            OGRGeometry* geometry = nullptr;
            ASSERT_EQ(OGRGeometryFactory::createFromWkt(wkt.c_str(), nullptr, &geometry),
                      OGRERR_NONE);
            feature.SetGeometryDirectly(geometry);
            ASSERT_EQ(layer->CreateFeature(&feature), OGRERR_NONE);
        }
    }
}

TEST(OgrLineReader, ReadsLinesAndMultiLinePartsExactly_WithZOrNaN) {
    TempDir dir;
    const std::string path = (dir.path() / "lines.gpkg").string();
    writeLayers(path, {{"roads",
                        {"LINESTRING Z (1.5 2.25 10, 3 4 11, 5 6.125 12)",
                         "MULTILINESTRING ((7 8, 9 10), (11 12, 13 14, 15 16))"}}});
    const LineLayer layer = readOgrLines(path, "", "--breaklines");
    EXPECT_EQ(layer.layerName, "roads");
    EXPECT_TRUE(layer.hasZ);
    EXPECT_FALSE(layer.crsWkt.empty());
    ASSERT_EQ(layer.lines.size(), 3U);
    EXPECT_EQ(layer.lines[0], (std::vector<Point3>{{1.5, 2.25, 10}, {3, 4, 11}, {5, 6.125, 12}}));
    ASSERT_EQ(layer.lines[2].size(), 3U);
    EXPECT_EQ(layer.lines[2][1].x, 13.0);
    EXPECT_TRUE(std::isnan(layer.lines[1][0].z)); // a 2D line has no z
    EXPECT_EQ(layer.featureIds, (std::vector<std::int64_t>{1, 2, 2}));
}

TEST(OgrLineReader, ChoosesTheLayerBySuffixOrByName_AndRefusesAnAmbiguousSource) {
    TempDir dir;
    const std::string path = (dir.path() / "two.gpkg").string();
    writeLayers(path, {{"a", {"LINESTRING (0 0, 1 1)"}}, {"b", {"LINESTRING (2 2, 3 3)"}}});
    EXPECT_EQ(readOgrLines(path + "|layername=b", "", "--breaklines").lines[0][0].x, 2.0);
    EXPECT_EQ(readOgrLines(path, "a", "--breaklines").lines[0][0].x, 0.0);
    try {
        (void)readOgrLines(path, "", "--breaklines");
        FAIL() << "two layers and no name";
    } catch (const InvalidInputError& error) {
        EXPECT_NE(std::string(error.what()).find("holds 2 layers ('a', 'b')"), std::string::npos)
            << error.what();
    }
    EXPECT_THROW((void)readOgrLines(path, "c", "--breaklines"), InvalidInputError);
}

TEST(OgrLineReader, RefusesAPolygonFeature_NamingItsFid) {
    TempDir dir;
    const std::string path = (dir.path() / "mixed.gpkg").string();
    writeLayers(path, {{"mixed", {"LINESTRING (0 0, 1 1)", "POLYGON ((0 0, 1 0, 1 1, 0 0))"}}});
    try {
        (void)readOgrLines(path, "", "breaklines");
        FAIL() << "a polygon among the lines";
    } catch (const InvalidInputError& error) {
        const std::string message = error.what();
        EXPECT_NE(message.find("breaklines"), std::string::npos) << message;
        EXPECT_NE(message.find("feature 2 is a Polygon"), std::string::npos) << message;
    }
}

TEST(OgrLineReader, APolygonWithANaNVertexIsRefusedAsNotFinite_NotAsACrossing) {
    TempDir dir;
    const std::string path = (dir.path() / "nan.gpkg").string();
    writeLayers(path, {{"areas", {}}});
    {
        GDALDatasetUniquePtr dataset(
            GDALDataset::Open(path.c_str(), GDAL_OF_VECTOR | GDAL_OF_UPDATE));
        ASSERT_TRUE(dataset);
        OGRLayer* layer = dataset->GetLayerByName("areas");
        OGRLinearRing ring;
        ring.addPoint(0.0, 0.0);
        ring.addPoint(10.0, 0.0);
        ring.addPoint(10.0, std::nan(""));
        ring.addPoint(0.0, 10.0);
        ring.closeRings();
        OGRPolygon polygon;
        polygon.addRing(&ring);
        OGRFeature feature(layer->GetLayerDefn());
        feature.SetGeometry(&polygon);
        ASSERT_EQ(layer->CreateFeature(&feature), OGRERR_NONE);
    }
    try {
        (void)readOgrPolygons(path, "", "clip");
        FAIL() << "a NaN vertex was taken";
    } catch (const InvalidInputError& error) {
        const std::string message = error.what();
        EXPECT_NE(message.find("feature 1: point 3 is not finite"), std::string::npos) << message;
        EXPECT_EQ(message.find("crosses"), std::string::npos) << message;
    }
}

TEST(OgrLineReader, AGeoPackageLayerStoredWithoutCrs_HasNoCrs_NotAnUndefinedGeographicOne) {
    TempDir dir;
    const std::string path = (dir.path() / "nocrs.gpkg").string();
    initialiseGdal();
    {
        GDALDriver* driver = GetGDALDriverManager()->GetDriverByName("GPKG");
        GDALDatasetUniquePtr dataset(driver->Create(path.c_str(), 0, 0, 0, GDT_Unknown, nullptr));
        ASSERT_TRUE(dataset);
        // No CRS: GDAL files the layer under srs_id 0, "Undefined geographic SRS".
        OGRLayer* layer = dataset->CreateLayer("lines", nullptr, wkbLineString, nullptr);
        ASSERT_NE(layer, nullptr);
        OGRFeature feature(layer->GetLayerDefn());
        OGRGeometry* line = nullptr;
        ASSERT_EQ(OGRGeometryFactory::createFromWkt("LINESTRING (455300 5102900, 456000 5103000)",
                                                    nullptr, &line),
                  OGRERR_NONE);
        feature.SetGeometryDirectly(line);
        ASSERT_EQ(layer->CreateFeature(&feature), OGRERR_NONE);
    }
    {
        GDALDatasetUniquePtr dataset(GDALDataset::Open(path.c_str(), GDAL_OF_VECTOR));
        const OGRSpatialReference* srs = dataset->GetLayer(0)->GetSpatialRef();
        ASSERT_NE(srs, nullptr) << "GDAL reports no CRS at all: the case is not the one tested";
        ASSERT_STREQ(srs->GetName(), "Undefined geographic SRS");
    }
    const LineLayer lines = readOgrLines(path, "", "breaklines");
    EXPECT_TRUE(lines.crsWkt.empty()) << lines.crsWkt;
    ASSERT_EQ(lines.lines.size(), 1U);
}

TEST(OgrLineReader, AnEmptyLayerGivesNoLines_AndAMissingFileAnIoError) {
    TempDir dir;
    const std::string path = (dir.path() / "empty.gpkg").string();
    writeLayers(path, {{"nothing", {}}});
    EXPECT_TRUE(readOgrLines(path, "", "--breaklines").lines.empty());
    EXPECT_THROW((void)readOgrLines((dir.path() / "absent.gpkg").string(), "", "--breaklines"),
                 IoError);
}

} // namespace
} // namespace terratin::io

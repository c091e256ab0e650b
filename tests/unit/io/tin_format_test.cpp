#include "terratin/io/tin_format.hpp"

#include "terratin/error.hpp"
#include "terratin/io/tin_writer.hpp"

#include <gtest/gtest.h>

namespace terratin::io {
namespace {

TEST(TinFormatNames, ParsesEveryFormat_WhenNamedCaseInsensitively) {
    EXPECT_EQ(parseTinFormat("FGB"), TinFormat::FlatGeobuf);
    EXPECT_EQ(parseTinFormat("FlatGeobuf"), TinFormat::FlatGeobuf);
    EXPECT_EQ(parseTinFormat("2dm"), TinFormat::TwoDm);
    EXPECT_EQ(parseTinFormat("PLY"), TinFormat::Ply);
    EXPECT_EQ(parseTinFormat("obj"), TinFormat::Obj);
    EXPECT_EQ(parseTinFormat("LandXML"), TinFormat::LandXml);
    EXPECT_THROW(parseTinFormat("dxf"), InvalidInputError);
}

TEST(TinFormatNames, FollowsExtension_WhenPathNamesAMeshFormat) {
    EXPECT_EQ(tinFormatFromPath("hood.fgb"), TinFormat::FlatGeobuf);
    EXPECT_EQ(tinFormatFromPath("hood.2DM"), TinFormat::TwoDm);
    EXPECT_EQ(tinFormatFromPath("a/b/hood.ply"), TinFormat::Ply);
    EXPECT_EQ(tinFormatFromPath("hood.obj"), TinFormat::Obj);
    EXPECT_EQ(tinFormatFromPath("hood.xml"), TinFormat::LandXml);
    EXPECT_EQ(tinFormatFromPath("hood.landxml"), TinFormat::LandXml);
    EXPECT_THROW(tinFormatFromPath("hood.stl"), InvalidInputError);
}

TEST(TinFormatNames, NamesEveryFormat_WhenReporting) {
    EXPECT_EQ(tinFormatName(TinFormat::GeoPackage), "GPKG");
    EXPECT_EQ(tinFormatName(TinFormat::FlatGeobuf), "FlatGeobuf");
    EXPECT_EQ(tinFormatName(TinFormat::LandXml), "LandXML");
    EXPECT_TRUE(isOgrFormat(TinFormat::Shapefile));
    EXPECT_FALSE(isOgrFormat(TinFormat::Ply));
}

TEST(TinWriteOptionsCheck, RefusesGeoPackageOnlyOptions_WhenFormatIsAnother) {
    TinWriteOptions options;
    options.format = TinFormat::FlatGeobuf;
    EXPECT_NO_THROW(checkTinWriteOptions(options));
    options.spatialIndex = false; // FlatGeobuf has an index too
    EXPECT_NO_THROW(checkTinWriteOptions(options));
    options.appendLayer = true;
    EXPECT_THROW(checkTinWriteOptions(options), InvalidInputError);
    options = {};
    options.format = TinFormat::Obj;
    options.spatialIndex = false;
    EXPECT_THROW(checkTinWriteOptions(options), InvalidInputError);
}

TEST(TinWriteOptionsCheck, NamesNodeAndEdgeLayers_AfterTheTriangleLayer) {
    EXPECT_EQ(nodeLayerName("tin"), "nodes");
    EXPECT_EQ(edgeLayerName("tin"), "edges");
    EXPECT_EQ(nodeLayerName("hood"), "hood_nodes");
    EXPECT_EQ(edgeLayerName("hood"), "hood_edges");
}

} // namespace
} // namespace terratin::io

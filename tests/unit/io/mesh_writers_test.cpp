// The mesh formats written by writeTin and read back by the independent readers of
// tests/support/mesh_readers: exact coordinates, the same triangles, the header facts, and
// the atomic-output guarantees every format shares.

#include "terratin/io/tin_writer.hpp"

#include "mesh_readers.hpp"
#include "temporary_directory.hpp"
#include "terratin/error.hpp"

#include <ogr_spatialref.h>

#include "ogr_test_support.hpp"

#include <gtest/gtest.h>

#include <cpl_conv.h>

#include <cmath>
#include <string>
#include <tuple>
#include <vector>

namespace terratin::io {
namespace {

using test::TemporaryDirectory;

using test::utm10nWkt;

TinWriteOptions optionsFor(TinFormat format, std::string crsWkt = {}) {
    TinWriteOptions options;
    options.format = format;
    options.crsWkt = std::move(crsWkt);
    return options;
}

/// Coordinates that need all 17 significant digits, and ones a short decimal cannot hold.
TinMesh awkwardMesh() {
    TinMesh mesh = test::gridTin(4);
    mesh.vertices[5].z = 0.1 + 0.2;          // 0.30000000000000004
    mesh.vertices[6].x = 500010.00000000006; // a hair above a round easting
    mesh.vertices[9].z = -1e-300;            // tiny and negative
    mesh.vertices[10].z = 8848.860000000001;
    return mesh;
}

TEST(TwoDmWriter, ReadsBackExactly_WhenWrittenAndParsed) {
    TemporaryDirectory directory;
    const TinMesh mesh = awkwardMesh();
    TinWriteOptions options = optionsFor(TinFormat::TwoDm);
    options.layerName = "hood";
    const TinWriteResult result = writeTin(mesh, directory / "tin.2dm", options);
    EXPECT_EQ(result.features, mesh.vertexCount() + mesh.triangleCount());
    const test::ReadMesh read = test::readTwoDm(directory / "tin.2dm");
    test::expectSameMesh(read, mesh);
    EXPECT_EQ(read.name, "hood");
    EXPECT_EQ(read.materials, std::vector<int>(mesh.triangleCount(), 1));
    EXPECT_EQ(directory.entries(), (std::set<std::string>{"tin.2dm"}));
}

TEST(PlyWriter, ReadsBackExactly_WhenBinaryLittleEndian) {
    TemporaryDirectory directory;
    const TinMesh mesh = awkwardMesh();
    writeTin(mesh, directory / "tin.ply", optionsFor(TinFormat::Ply, utm10nWkt()));
    const test::ReadMesh read = test::readPly(directory / "tin.ply");
    test::expectSameMesh(read, mesh);
    OGRSpatialReference crs;
    ASSERT_EQ(crs.importFromWkt(read.crs.c_str()), OGRERR_NONE) << read.crs;
    OGRSpatialReference utm;
    utm.importFromEPSG(26910);
    EXPECT_TRUE(crs.IsSame(&utm)) << read.crs;
    // Header + 24 bytes per vertex + 13 bytes per face, nothing else.
    const std::string bytes = test::fileBytes(directory / "tin.ply");
    const auto headerEnd = bytes.find("end_header\n") + 11;
    EXPECT_EQ(bytes.size() - headerEnd, 24 * mesh.vertexCount() + 13 * mesh.triangleCount());
}

// Regression: the header said "comment crs <WKT>"; MDAL reads PLY comments as "key: value",
// so QGIS 3.22 opened the mesh layer without a CRS. tests/qgis checks the same in QGIS itself.
TEST(PlyWriter, WritesCrsCommentWithColon_SoQgisMeshLayerHasCrs) {
    TemporaryDirectory directory;
    writeTin(test::gridTin(3), directory / "tin.ply", optionsFor(TinFormat::Ply, utm10nWkt()));
    const std::string bytes = test::fileBytes(directory / "tin.ply");
    const std::string header = bytes.substr(0, bytes.find("end_header\n"));
    const auto line = header.find("\ncomment crs: ");
    ASSERT_NE(line, std::string::npos) << header;
    const auto wktBegin = line + 14;
    const std::string wkt = header.substr(wktBegin, header.find('\n', wktBegin) - wktBegin);
    OGRSpatialReference crs;
    ASSERT_EQ(crs.importFromWkt(wkt.c_str()), OGRERR_NONE) << wkt;
    OGRSpatialReference utm;
    utm.importFromEPSG(26910);
    EXPECT_TRUE(crs.IsSame(&utm)) << wkt;
    EXPECT_EQ(header.find("\ncomment crs "), std::string::npos) << header;
}

TEST(PlyWriter, WritesNoCrsComment_WhenThereIsNoCrs) {
    TemporaryDirectory directory;
    writeTin(test::gridTin(3), directory / "tin.ply", optionsFor(TinFormat::Ply));
    EXPECT_TRUE(test::readPly(directory / "tin.ply").crs.empty());
}

TEST(ObjWriter, ReadsBackExactly_WhenLocalOriginIsAddedBack) {
    TemporaryDirectory directory;
    const TinMesh mesh = awkwardMesh();
    TinWriteOptions options = optionsFor(TinFormat::Obj, utm10nWkt());
    options.layerName = "terrain";
    writeTin(mesh, directory / "tin.obj", options);
    const test::ReadMesh read = test::readObj(directory / "tin.obj");
    test::expectSameMesh(read, mesh);
    EXPECT_EQ(read.name, "terrain");
    // The floor of the smallest easting / northing; z stays absolute.
    EXPECT_EQ(read.origin.x, 500000.0);
    EXPECT_EQ(read.origin.y, 5000000.0);
    EXPECT_EQ(read.origin.z, 0.0);
    const std::string text = test::fileBytes(directory / "tin.obj");
    EXPECT_NE(text.find("# CRS: NAD83 / UTM zone 10N (EPSG:26910)"), std::string::npos);
    // Local coordinates are small: the first vertex is at the origin exactly.
    EXPECT_NE(text.find("\nv 0 0 1234.5\n"), std::string::npos);
}

TEST(ObjWriter, FallsBackToZeroOrigin_WhenSubtractionWouldNotBeExact) {
    // Around zero with a tiny coordinate: x - floor(min x) = x + 1 is not exact for 1e-20.
    TemporaryDirectory directory;
    TinMesh mesh;
    mesh.vertices = {{-0.5, 0.0, 1.0}, {1e-20, 0.0, 2.0}, {0.0, 1.0, 3.0}};
    mesh.sourceIndex = {0, 1, 2};
    mesh.triangles = {0, 1, 2};
    mesh.neighbours = {kNoNeighbour, kNoNeighbour, kNoNeighbour};
    writeTin(mesh, directory / "tin.obj", optionsFor(TinFormat::Obj));
    const test::ReadMesh read = test::readObj(directory / "tin.obj");
    EXPECT_EQ(read.origin.x, 0.0);
    test::expectSameMesh(read, mesh);
}

TEST(MeshWriters, KeepOldOutputAndLeaveNoTemporaries_WhenCancelledOrRefused) {
    for (const auto& [format, name] :
         {std::tuple{TinFormat::TwoDm, "tin.2dm"}, std::tuple{TinFormat::Ply, "tin.ply"},
          std::tuple{TinFormat::Obj, "tin.obj"}, std::tuple{TinFormat::LandXml, "tin.xml"}}) {
        TemporaryDirectory directory;
        std::ofstream(directory / name) << "precious";
        // Refused without overwrite, before anything is written.
        EXPECT_THROW(writeTin(test::gridTin(3), directory / name, optionsFor(format)),
                     InvalidInputError)
            << name;
        // Cancelled at the last report before the rename.
        TinWriteOptions options = optionsFor(format);
        options.overwrite = true;
        EXPECT_THROW(
            writeTin(test::gridTin(3), directory / name, options,
                     [](double, std::string_view message) { return message != "Finishing"; }),
            Cancelled)
            << name;
        EXPECT_EQ(test::fileBytes(directory / name), "precious") << name;
        EXPECT_EQ(directory.entries(), (std::set<std::string>{name})) << name;
        // And replaced when allowed.
        writeTin(test::gridTin(3), directory / name, options);
        EXPECT_NE(test::fileBytes(directory / name), "precious") << name;
        EXPECT_EQ(directory.entries(), (std::set<std::string>{name})) << name;
    }
}

TEST(MeshWriters, ReportIncreasingProgressEndingAtOne_WhenWriting) {
    // 2 * 199^2 = 79202 triangles and 40000 vertices: reports every 65536 records.
    const TinMesh mesh = test::gridTin(200);
    TemporaryDirectory directory;
    std::vector<double> fractions;
    writeTin(mesh, directory / "tin.2dm", optionsFor(TinFormat::TwoDm),
             [&](double fraction, std::string_view) {
                 fractions.push_back(fraction);
                 return true;
             });
    ASSERT_GE(fractions.size(), 4u);
    EXPECT_EQ(fractions.front(), 0.0);
    EXPECT_EQ(fractions.back(), 1.0);
    EXPECT_TRUE(std::is_sorted(fractions.begin(), fractions.end()));
}

TEST(MeshWriters, StopInTheirRecords_WhenCancelledThere) {
    // 40000 vertices and 79202 triangles: the report at record 65536 is a face's.
    const TinMesh mesh = test::gridTin(200);
    for (const auto& [format, name] :
         {std::tuple{TinFormat::TwoDm, "tin.2dm"}, std::tuple{TinFormat::Ply, "tin.ply"},
          std::tuple{TinFormat::Obj, "tin.obj"}, std::tuple{TinFormat::LandXml, "tin.xml"}}) {
        TemporaryDirectory directory;
        std::string stoppedAt;
        EXPECT_THROW(writeTin(mesh, directory / name, optionsFor(format),
                              [&](double fraction, std::string_view message) {
                                  if (fraction == 0.0)
                                      return true;
                                  stoppedAt = message;
                                  return false;
                              }),
                     Cancelled)
            << name;
        EXPECT_NE(stoppedAt.find("Writing"), std::string::npos) << name << ": " << stoppedAt;
        EXPECT_TRUE(directory.entries().empty()) << name;
    }
}

TEST(MeshWriters, RefuseOptionsOfTheVectorFormats_WhenMeshFormat) {
    TemporaryDirectory directory;
    TinWriteOptions options = optionsFor(TinFormat::Ply);
    options.nodes = true;
    EXPECT_THROW(writeTin(test::gridTin(3), directory / "tin.ply", options), InvalidInputError);
    options = optionsFor(TinFormat::TwoDm);
    options.qgisStyle = true;
    EXPECT_THROW(writeTin(test::gridTin(3), directory / "tin.2dm", options), InvalidInputError);
    EXPECT_TRUE(directory.entries().empty());
}

} // namespace
} // namespace terratin::io

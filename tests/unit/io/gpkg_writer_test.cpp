// The GeoPackage writer's proofs: SQLite's rtreecheck passes on every index it writes, OGR's
// spatial filter returns exactly what a brute-force scan does, the index stays right when
// OGR edits the file afterwards (the triggers), the blobs are GDAL's own bytes, and empty,
// tiny, appended, node and edge layers take the same path.

#include "terratin/io/tin_writer.hpp"

#include "distributions.hpp"
#include "gpkg_feature_table.hpp"
#include "gpkg_spatial_index.hpp"
#include "mesh_readers.hpp"
#include "ogr_test_support.hpp"
#include "sqlite_query.hpp"
#include "temporary_directory.hpp"
#include "terratin/error.hpp"
#include "terratin/gdal_error.hpp"
#include "terratin/triangulate/triangulate.hpp"

#include <gdal_priv.h>
#include <ogr_feature.h>
#include <ogr_geometry.h>
#include <ogrsf_frmts.h>
#include <sqlite3.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <memory>
#include <random>
#include <set>
#include <string>
#include <vector>

namespace terratin::io {
namespace {

using test::rtreeCheck;
using test::sqliteText;
using test::TemporaryDirectory;

/// A Delaunay TIN of `count` uniform points spread over 30 km at UTM coordinates, where
/// float32 boxes are coarser than the coordinates (the R*Tree must round outwards).
TinMesh utmTin(std::size_t count, std::uint64_t seed = 11) {
    std::vector<Point3> points = bench::generatePoints(bench::Distribution::Uniform, count, seed);
    for (Point3& p : points) {
        p.x = 587000.0 + 30000.0 * p.x;
        p.y = 5013000.0 + 24000.0 * p.y;
        p.z = 1000.0 + 500.0 * p.z;
    }
    return triangulate(points).mesh;
}

TinWriteOptions geoPackageOptions() {
    TinWriteOptions options;
    options.format = TinFormat::GeoPackage;
    options.crsWkt = test::utm10nWkt();
    return options;
}

GDALDatasetUniquePtr openGeoPackage(const std::filesystem::path& path, bool update = false) {
    initialiseGdal();
    return GDALDatasetUniquePtr(GDALDataset::Open(
        path.c_str(), GDAL_OF_VECTOR | (update ? GDAL_OF_UPDATE : GDAL_OF_READONLY)));
}

struct Window {
    double minX, minY, maxX, maxY;
};

std::vector<Window> randomWindows(const OGREnvelope& extent, int count, unsigned seed) {
    std::mt19937 random(seed);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    std::vector<Window> windows;
    const double width = extent.MaxX - extent.MinX;
    const double height = extent.MaxY - extent.MinY;
    for (int i = 0; i < count; ++i) {
        // Sizes from a fraction of a triangle to a third of the extent, some past its edge.
        const double size = std::pow(10.0, -4.0 + 3.5 * unit(random));
        const double x = extent.MinX - 0.1 * width + 1.2 * width * unit(random);
        const double y = extent.MinY - 0.1 * height + 1.2 * height * unit(random);
        windows.push_back({x, y, x + size * width, y + size * height});
    }
    return windows;
}

/// Fids whose envelope meets the window grown by `margin` on every side, found by a scan.
std::set<GIntBig> envelopeHits(const std::vector<std::pair<GIntBig, OGREnvelope>>& all,
                               const Window& w, double margin) {
    std::set<GIntBig> hits;
    for (const auto& [fid, e] : all)
        if (e.MinX <= w.maxX + margin && w.minX - margin <= e.MaxX && e.MinY <= w.maxY + margin &&
            w.minY - margin <= e.MaxY)
            hits.insert(fid);
    return hits;
}

/// The ids the R*Tree itself returns for the window, by SQL on the rtree table.
std::set<GIntBig> rtreeHits(const std::filesystem::path& path, const std::string& layer,
                            const Window& w) {
    sqlite3* db = nullptr;
    EXPECT_EQ(sqlite3_open_v2(path.c_str(), &db, SQLITE_OPEN_READONLY, nullptr), SQLITE_OK);
    sqlite3_stmt* statement = nullptr;
    const std::string sql = "SELECT id FROM \"rtree_" + layer +
                            "_geom\" WHERE minx <= ? AND maxx >= ? AND miny <= ? AND maxy >= ?";
    EXPECT_EQ(sqlite3_prepare_v2(db, sql.c_str(), -1, &statement, nullptr), SQLITE_OK);
    sqlite3_bind_double(statement, 1, w.maxX);
    sqlite3_bind_double(statement, 2, w.minX);
    sqlite3_bind_double(statement, 3, w.maxY);
    sqlite3_bind_double(statement, 4, w.minY);
    std::set<GIntBig> hits;
    while (sqlite3_step(statement) == SQLITE_ROW)
        hits.insert(sqlite3_column_int64(statement, 0));
    sqlite3_finalize(statement);
    sqlite3_close(db);
    return hits;
}

/// For each window: the R*Tree returns every feature whose envelope meets it, and no other
/// beyond the float32 rounding of its boxes (0.5 m at northings of 5e6; a 1 m margin); and
/// OGR's spatial filter, which tests the geometries of the R*Tree's candidates, returns
/// exactly the features whose geometry meets the window, found by testing every feature.
void expectFilterMatchesBruteForce(const std::filesystem::path& path, const std::string& name,
                                   const std::vector<Window>& windows) {
    const auto dataset = openGeoPackage(path);
    ASSERT_TRUE(dataset);
    OGRLayer& layer = *dataset->GetLayerByName(name.c_str());
    ASSERT_TRUE(layer.TestCapability(OLCFastSpatialFilter)) << "no spatial index";
    std::vector<std::pair<GIntBig, OGREnvelope>> all;
    std::vector<std::pair<GIntBig, std::unique_ptr<OGRGeometry>>> geometries;
    for (const auto& feature : layer) {
        OGREnvelope envelope;
        feature->GetGeometryRef()->getEnvelope(&envelope);
        all.emplace_back(feature->GetFID(), envelope);
        geometries.emplace_back(feature->GetFID(), feature->StealGeometry());
    }
    constexpr double kFloatMarginM = 1.0;
    for (const Window& w : windows) {
        const std::string where = "window " + std::to_string(w.minX) + " " +
                                  std::to_string(w.minY) + " " + std::to_string(w.maxX) + " " +
                                  std::to_string(w.maxY);
        const std::set<GIntBig> candidates = rtreeHits(path, name, w);
        const std::set<GIntBig> exact = envelopeHits(all, w, 0.0);
        EXPECT_TRUE(std::includes(candidates.begin(), candidates.end(), exact.begin(), exact.end()))
            << "the R*Tree misses features, " << where;
        const std::set<GIntBig> loose = envelopeHits(all, w, kFloatMarginM);
        EXPECT_TRUE(std::includes(loose.begin(), loose.end(), candidates.begin(), candidates.end()))
            << "the R*Tree returns far features, " << where;

        OGRPolygon window;
        OGRLinearRing ring;
        ring.addPoint(w.minX, w.minY);
        ring.addPoint(w.maxX, w.minY);
        ring.addPoint(w.maxX, w.maxY);
        ring.addPoint(w.minX, w.maxY);
        ring.closeRings();
        window.addRing(&ring);
        std::set<GIntBig> intersecting;
        for (const auto& [fid, geometry] : geometries)
            if (geometry->Intersects(&window))
                intersecting.insert(fid);
        layer.SetSpatialFilterRect(w.minX, w.minY, w.maxX, w.maxY);
        std::set<GIntBig> filtered;
        for (const auto& feature : layer)
            filtered.insert(feature->GetFID());
        EXPECT_EQ(filtered, intersecting) << where;
    }
}

OGREnvelope layerExtent(const std::filesystem::path& path, const std::string& name) {
    const auto dataset = openGeoPackage(path);
    OGREnvelope extent;
    EXPECT_EQ(dataset->GetLayerByName(name.c_str())->GetExtent(&extent, TRUE), OGRERR_NONE);
    return extent;
}

TEST(GeoPackageIndex, PassesRtreecheckAndFiltersLikeBruteForce_WhenManyTriangles) {
    TemporaryDirectory directory;
    const TinMesh mesh = utmTin(20000);
    writeTin(mesh, directory / "tin.gpkg", geoPackageOptions());
    EXPECT_EQ(rtreeCheck(directory / "tin.gpkg", "tin"), "ok");
    EXPECT_EQ(sqliteText(directory / "tin.gpkg", "SELECT count(*) FROM rtree_tin_geom_rowid"),
              std::to_string(mesh.triangleCount()));
    {
        const auto dataset = openGeoPackage(directory / "tin.gpkg");
        ASSERT_TRUE(dataset);
        EXPECT_EQ(dataset->GetLayerByName("tin")->GetFeatureCount(),
                  static_cast<GIntBig>(mesh.triangleCount()));
    }
    expectFilterMatchesBruteForce(
        directory / "tin.gpkg", "tin",
        randomWindows(layerExtent(directory / "tin.gpkg", "tin"), 100, 3));
}

TEST(GeoPackageIndex, StaysRightThroughOgrEdits_WhenFeaturesAreDeletedInsertedAndMoved) {
    TemporaryDirectory directory;
    const TinMesh mesh = utmTin(3000);
    writeTin(mesh, directory / "tin.gpkg", geoPackageOptions());
    {
        const auto dataset = openGeoPackage(directory / "tin.gpkg", true);
        ASSERT_TRUE(dataset);
        OGRLayer& layer = *dataset->GetLayerByName("tin");
        for (GIntBig fid = 1; fid <= 200; fid += 3)
            ASSERT_EQ(layer.DeleteFeature(fid), OGRERR_NONE);
        // Move features far to the east (update of the geometry, same fid).
        for (GIntBig fid = 500; fid < 600; ++fid) {
            OGRFeatureUniquePtr feature(layer.GetFeature(fid));
            ASSERT_TRUE(feature);
            feature->GetGeometryRef()->toPolygon()->getExteriorRing()->setPoint(1, 650000.0,
                                                                                5020000.0, 1.0);
            ASSERT_EQ(layer.SetFeature(feature.get()), OGRERR_NONE);
        }
        // New features, with the driver's fids.
        for (int i = 0; i < 50; ++i) {
            OGRFeatureUniquePtr feature(OGRFeature::CreateFeature(layer.GetLayerDefn()));
            OGRLinearRing ring;
            const double x = 640000.0 + 10.0 * i;
            ring.addPoint(x, 5030000.0, 1.0);
            ring.addPoint(x + 5.0, 5030000.0, 1.0);
            ring.addPoint(x, 5030005.0, 1.0);
            ring.closeRings();
            OGRPolygon polygon;
            polygon.addRing(&ring);
            feature->SetGeometry(&polygon);
            ASSERT_EQ(layer.CreateFeature(feature.get()), OGRERR_NONE);
        }
    }
    EXPECT_EQ(rtreeCheck(directory / "tin.gpkg", "tin"), "ok");
    {
        const auto dataset = openGeoPackage(directory / "tin.gpkg");
        EXPECT_EQ(dataset->GetLayerByName("tin")->GetFeatureCount(),
                  static_cast<GIntBig>(mesh.triangleCount()) - 67 + 50);
    }
    std::vector<Window> windows = randomWindows(layerExtent(directory / "tin.gpkg", "tin"), 60, 5);
    windows.push_back({649999.0, 5019999.0, 650001.0, 5020001.0}); // the moved corners
    windows.push_back({640000.0, 5030000.0, 640600.0, 5030010.0}); // the new features
    expectFilterMatchesBruteForce(directory / "tin.gpkg", "tin", windows);
}

TEST(GeoPackageIndex, IsValid_WhenTheLayerHasOneOrTwoTriangles) {
    TemporaryDirectory directory;
    const TinMesh two = test::gridTin(2);
    TinMesh one = two;
    one.triangles.resize(3);
    one.neighbours.assign(3, kNoNeighbour);
    const std::vector<std::pair<std::string, const TinMesh*>> meshes = {{"one", &one},
                                                                        {"two", &two}};
    for (const auto& [name, mesh] : meshes) {
        const auto path = directory / (name + ".gpkg");
        writeTin(*mesh, path, geoPackageOptions());
        EXPECT_EQ(rtreeCheck(path, "tin"), "ok") << name;
        const auto dataset = openGeoPackage(path);
        ASSERT_TRUE(dataset) << name;
        OGRLayer& layer = *dataset->GetLayerByName("tin");
        EXPECT_TRUE(layer.TestCapability(OLCFastSpatialFilter)) << name;
        layer.SetSpatialFilterRect(499999.0, 4999999.0, 500011.0, 5000011.0);
        EXPECT_EQ(layer.GetFeatureCount(), static_cast<GIntBig>(mesh->triangleCount())) << name;
        layer.SetSpatialFilterRect(0.0, 0.0, 1.0, 1.0);
        EXPECT_EQ(layer.GetFeatureCount(), 0) << name;
    }
}

TEST(GeoPackageIndex, IsValidAndFollowsLaterInserts_WhenTheLayerIsEmpty) {
    // writeTin refuses a mesh without triangles, so the empty index is written directly into a
    // layer OGR created, as the writer does.
    TemporaryDirectory directory;
    const auto path = directory / "empty.gpkg";
    initialiseGdal();
    {
        GDALDriver* driver = GetGDALDriverManager()->GetDriverByName("GPKG");
        GDALDatasetUniquePtr dataset(driver->Create(path.c_str(), 0, 0, 0, GDT_Unknown, nullptr));
        OGRSpatialReference srs;
        srs.importFromEPSG(26910);
        const char* options[] = {"SPATIAL_INDEX=NO", "GEOMETRY_NAME=geom", nullptr};
        ASSERT_NE(dataset->CreateLayer("tin", &srs, wkbPolygon25D, const_cast<char**>(options)),
                  nullptr);
    }
    {
        detail::SqliteConnection db("test", path, path);
        db.execute("BEGIN");
        detail::GpkgFeatureTable table(db, "tin");
        detail::writeGpkgSpatialIndex(db, {"tin", "geom", "fid"}, detail::PackedRtree({}, 51),
                                      [](std::uint64_t) {});
        table.finish(0, {});
        db.execute("COMMIT");
        db.close();
    }
    EXPECT_EQ(rtreeCheck(path, "tin"), "ok");
    {
        const auto dataset = openGeoPackage(path, true);
        OGRLayer& layer = *dataset->GetLayerByName("tin");
        EXPECT_TRUE(layer.TestCapability(OLCFastSpatialFilter));
        EXPECT_EQ(layer.GetFeatureCount(), 0);
        OGRFeatureUniquePtr feature(OGRFeature::CreateFeature(layer.GetLayerDefn()));
        OGRLinearRing ring;
        ring.addPoint(10.0, 10.0, 1.0);
        ring.addPoint(20.0, 10.0, 1.0);
        ring.addPoint(10.0, 20.0, 1.0);
        ring.closeRings();
        OGRPolygon polygon;
        polygon.addRing(&ring);
        feature->SetGeometry(&polygon);
        ASSERT_EQ(layer.CreateFeature(feature.get()), OGRERR_NONE);
    }
    EXPECT_EQ(rtreeCheck(path, "tin"), "ok");
    EXPECT_EQ(sqliteText(path, "SELECT count(*) FROM rtree_tin_geom"), "1");
}

TEST(GeoPackageIndex, IndexesNodesAndEdges_WhenAppendedToAnExistingGeoPackage) {
    TemporaryDirectory directory;
    const auto path = directory / "site.gpkg";
    writeTin(utmTin(500, 1), path, geoPackageOptions());
    TinWriteOptions options = geoPackageOptions();
    options.appendLayer = true;
    options.layerName = "second";
    options.nodes = true;
    options.edges = true;
    const TinMesh mesh = utmTin(2000, 2);
    writeTin(mesh, path, options);
    for (const char* layer : {"tin", "second", "second_nodes", "second_edges"})
        EXPECT_EQ(rtreeCheck(path, layer), "ok") << layer;
    for (const char* name : {"second", "second_nodes", "second_edges"})
        expectFilterMatchesBruteForce(path, name, randomWindows(layerExtent(path, name), 30, 9));
    const auto dataset = openGeoPackage(path);
    ASSERT_TRUE(dataset);
    EXPECT_EQ(dataset->GetLayerByName("second_nodes")->GetFeatureCount(),
              static_cast<GIntBig>(mesh.vertexCount()));
}

TEST(GeoPackageIndex, WritesGeoPackage14Triggers_WhenTheFileIsVersion14) {
    TemporaryDirectory directory;
    const auto path = directory / "new.gpkg";
    writeTin(test::gridTin(3), path, geoPackageOptions());
    {
        sqlite3* db = nullptr;
        ASSERT_EQ(sqlite3_open(path.c_str(), &db), SQLITE_OK);
        ASSERT_EQ(sqlite3_exec(db, "PRAGMA user_version = 10400", nullptr, nullptr, nullptr),
                  SQLITE_OK);
        sqlite3_close(db);
    }
    TinWriteOptions options = geoPackageOptions();
    options.appendLayer = true;
    options.layerName = "v14";
    writeTin(utmTin(1000), path, options);
    const std::string triggers = sqliteText(
        path, "SELECT group_concat(name, ' ') FROM (SELECT name FROM sqlite_master WHERE "
              "type = 'trigger' AND name LIKE 'rtree_v14_geom_%' ORDER BY name)");
    EXPECT_EQ(triggers, "rtree_v14_geom_delete rtree_v14_geom_insert rtree_v14_geom_update2 "
                        "rtree_v14_geom_update4 rtree_v14_geom_update5 rtree_v14_geom_update6 "
                        "rtree_v14_geom_update7");
    {
        const auto dataset = openGeoPackage(path, true);
        ASSERT_TRUE(dataset);
        OGRLayer& layer = *dataset->GetLayerByName("v14");
        OGRFeatureUniquePtr feature(layer.GetFeature(10));
        ASSERT_TRUE(feature);
        feature->GetGeometryRef()->toPolygon()->getExteriorRing()->setPoint(0, 600000.0, 5000000.0,
                                                                            1.0);
        ASSERT_EQ(layer.SetFeature(feature.get()), OGRERR_NONE);
        ASSERT_EQ(layer.DeleteFeature(11), OGRERR_NONE);
    }
    EXPECT_EQ(rtreeCheck(path, "v14"), "ok");
    const auto dataset = openGeoPackage(path);
    OGRLayer& layer = *dataset->GetLayerByName("v14");
    layer.SetSpatialFilterRect(599999.0, 4999999.0, 600001.0, 5000001.0);
    EXPECT_EQ(layer.GetFeatureCount(), 1);
}

TEST(GeoPackageRows, StoresGdalsOwnGeometryBytesAndCounts_WhenWrittenDirectly) {
    TemporaryDirectory directory;
    const TinMesh mesh = test::gridTin(3);
    writeTin(mesh, directory / "ours.gpkg", geoPackageOptions());
    // The same first triangle through OGR.
    initialiseGdal();
    {
        GDALDriver* driver = GetGDALDriverManager()->GetDriverByName("GPKG");
        GDALDatasetUniquePtr dataset(
            driver->Create((directory / "ogr.gpkg").c_str(), 0, 0, 0, GDT_Unknown, nullptr));
        OGRSpatialReference srs;
        srs.importFromEPSG(26910);
        OGRLayer* layer = dataset->CreateLayer("tin", &srs, wkbPolygon25D, nullptr);
        OGRFeatureUniquePtr feature(OGRFeature::CreateFeature(layer->GetLayerDefn()));
        OGRLinearRing ring;
        for (const int corner : {0, 1, 2, 0}) {
            const Point3& p = mesh.vertices[mesh.triangles[static_cast<std::size_t>(corner)]];
            ring.addPoint(p.x, p.y, p.z);
        }
        OGRPolygon polygon;
        polygon.addRing(&ring);
        feature->SetGeometry(&polygon);
        ASSERT_EQ(layer->CreateFeature(feature.get()), OGRERR_NONE);
    }
    const std::string blob = "SELECT hex(geom) FROM tin WHERE fid = 1";
    EXPECT_EQ(sqliteText(directory / "ours.gpkg", blob), sqliteText(directory / "ogr.gpkg", blob));
    EXPECT_EQ(sqliteText(directory / "ours.gpkg",
                         "SELECT feature_count FROM gpkg_ogr_contents WHERE table_name = 'tin'"),
              std::to_string(mesh.triangleCount()));
    // The feature-count triggers OGR created are back after the bulk insert.
    EXPECT_EQ(sqliteText(directory / "ours.gpkg",
                         "SELECT count(*) FROM sqlite_master WHERE type = 'trigger' AND name LIKE "
                         "'trigger_%_feature_count_tin'"),
              "2");
    EXPECT_EQ(sqliteText(directory / "ours.gpkg",
                         "SELECT min_x || ' ' || max_y FROM gpkg_contents WHERE table_name = "
                         "'tin'"),
              "500000.0 5000020.0");
}

TEST(GeoPackageRows, KeepsTheExistingOutput_WhenAnOverwriteIsCancelledInTheIndex) {
    TemporaryDirectory directory;
    std::ofstream(directory / "tin.gpkg") << "the user's old file";
    TinWriteOptions options = geoPackageOptions();
    options.overwrite = true;
    const auto cancelInIndex = [](double, std::string_view message) {
        return message.find("spatial index") == std::string_view::npos;
    };
    EXPECT_THROW(writeTin(utmTin(2000), directory / "tin.gpkg", options, cancelInIndex), Cancelled);
    EXPECT_EQ(test::fileBytes(directory / "tin.gpkg"), "the user's old file");
    EXPECT_EQ(directory.entries(), (std::set<std::string>{"tin.gpkg"}));
}

TEST(GeoPackageRows, LeavesNothingBehind_WhenCancelledWhileWritingRowsOrIndex) {
    for (const std::string phase : {"Writing triangles", "Building spatial index"}) {
        TemporaryDirectory directory;
        const auto cancelIn = [&](double, std::string_view message) {
            return message.find(phase) == std::string_view::npos;
        };
        EXPECT_THROW(writeTin(utmTin(2000), directory / "tin.gpkg", geoPackageOptions(), cancelIn),
                     Cancelled)
            << phase;
        EXPECT_TRUE(directory.entries().empty()) << phase;
    }
}

} // namespace
} // namespace terratin::io

// runBuild end to end on real DEMs, checked from the written file alone: every vertex is a
// valid cell centre carrying that cell's exact elevation, the triangles are exactly Delaunay
// and cover the convex hull of the valid cells.

#include "terratin/pipeline/build_pipeline.hpp"

#include "mesh_invariants.hpp"
#include "terratin/error.hpp"
#include "terratin/triangulate/mesh_validation.hpp"

#include <gdal_priv.h>
#include <ogrsf_frmts.h>

#include "temporary_directory.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <utility>

namespace terratin {
namespace {

namespace fs = std::filesystem;

fs::path sharedDem(const std::string& name) {
    return fs::path(TERRATIN_SHARED_DEMS) / name;
}
using test::TemporaryDirectory;

// The raster band with its mask, as GDAL itself reports them.
struct ReferenceRaster {
    int width = 0;
    int height = 0;
    double geoTransform[6]{};
    std::vector<double> values;
    std::vector<unsigned char> valid;
    std::vector<Point3> validCentres;
};

ReferenceRaster readReference(const fs::path& path) {
    ReferenceRaster raster;
    std::unique_ptr<GDALDataset> dataset(
        GDALDataset::Open(path.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY));
    EXPECT_NE(dataset, nullptr);
    raster.width = dataset->GetRasterXSize();
    raster.height = dataset->GetRasterYSize();
    dataset->GetGeoTransform(raster.geoTransform);
    GDALRasterBand* band = dataset->GetRasterBand(1);
    const std::size_t cells = static_cast<std::size_t>(raster.width) * raster.height;
    raster.values.resize(cells);
    raster.valid.resize(cells);
    EXPECT_EQ(band->RasterIO(GF_Read, 0, 0, raster.width, raster.height, raster.values.data(),
                             raster.width, raster.height, GDT_Float64, 0, 0),
              CE_None);
    EXPECT_EQ(band->GetMaskBand()->RasterIO(GF_Read, 0, 0, raster.width, raster.height,
                                            raster.valid.data(), raster.width, raster.height,
                                            GDT_Byte, 0, 0),
              CE_None);
    const double* gt = raster.geoTransform;
    for (int row = 0; row < raster.height; ++row)
        for (int col = 0; col < raster.width; ++col) {
            const std::size_t i = static_cast<std::size_t>(row) * raster.width + col;
            if (raster.valid[i] == 0 || std::isnan(raster.values[i])) {
                raster.valid[i] = 0;
                continue;
            }
            raster.validCentres.push_back({gt[0] + (col + 0.5) * gt[1] + (row + 0.5) * gt[2],
                                           gt[3] + (col + 0.5) * gt[4] + (row + 0.5) * gt[5],
                                           raster.values[i]});
        }
    return raster;
}

// The written triangles, turned back into a TinMesh (vertices merged by exact x, y).
TinMesh readBackMesh(const fs::path& path, std::string& crsName) {
    std::unique_ptr<GDALDataset> dataset(
        GDALDataset::Open(path.c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY));
    EXPECT_NE(dataset, nullptr);
    OGRLayer* layer = dataset->GetLayer(0);
    EXPECT_EQ(wkbFlatten(layer->GetGeomType()), wkbPolygon);
    EXPECT_TRUE(wkbHasZ(layer->GetGeomType()));
    if (const OGRSpatialReference* srs = layer->GetSpatialRef())
        crsName = srs->GetName();
    TinMesh mesh;
    std::map<std::pair<double, double>, std::uint32_t> vertexIds;
    std::map<std::pair<std::uint32_t, std::uint32_t>, std::pair<std::size_t, std::size_t>> edges;
    for (const auto& feature : *layer) {
        const auto* polygon = feature->GetGeometryRef()->toPolygon();
        const OGRLinearRing* ring = polygon->getExteriorRing();
        EXPECT_EQ(ring->getNumPoints(), 4);
        for (int i = 0; i < 3; ++i) {
            const auto key = std::make_pair(ring->getX(i), ring->getY(i));
            const auto [it, added] =
                vertexIds.emplace(key, static_cast<std::uint32_t>(mesh.vertices.size()));
            if (added) {
                mesh.vertices.push_back({ring->getX(i), ring->getY(i), ring->getZ(i)});
                mesh.sourceIndex.push_back(it->second);
            } else {
                EXPECT_EQ(mesh.vertices[it->second].z, ring->getZ(i)) << "vertex z differs";
            }
            mesh.triangles.push_back(it->second);
        }
    }
    // Neighbours from shared edges.
    mesh.neighbours.assign(mesh.triangles.size(), kNoNeighbour);
    std::map<std::pair<std::uint32_t, std::uint32_t>, std::size_t> halfEdges;
    for (std::size_t k = 0; k < mesh.triangles.size(); ++k) {
        const std::size_t t = k / 3;
        const std::uint32_t from = mesh.triangles[k];
        const std::uint32_t to = mesh.triangles[3 * t + (k % 3 + 1) % 3];
        halfEdges[{from, to}] = k;
    }
    for (const auto& [edge, k] : halfEdges) {
        const auto twin = halfEdges.find({edge.second, edge.first});
        if (twin != halfEdges.end())
            mesh.neighbours[k] = static_cast<std::int32_t>(twin->second / 3);
    }
    return mesh;
}

void expectTinOfValidCells(const fs::path& dem, const std::string& expectedCrsFragment) {
    if (!fs::exists(dem))
        GTEST_SKIP() << dem << " not available";
    TemporaryDirectory directory;
    BuildOptions options;
    options.inputs = {dem.string()};
    options.output = directory.path() / "tin.gpkg";
    options.validate = true;
    const BuildReport report = runBuild(options);
    EXPECT_TRUE(report.validated);

    const ReferenceRaster raster = readReference(dem);
    EXPECT_EQ(report.points, raster.validCentres.size());
    EXPECT_EQ(report.duplicates, 0U);
    EXPECT_EQ(report.vertices, raster.validCentres.size());

    std::string crsName;
    const TinMesh mesh = readBackMesh(options.output, crsName);
    EXPECT_EQ(mesh.triangleCount(), report.triangles);
    EXPECT_NE(crsName.find(expectedCrsFragment), std::string::npos) << crsName;

    // Every vertex: an exact cell centre of a valid cell, with that cell's exact value.
    const double* gt = raster.geoTransform;
    std::size_t wrong = 0;
    for (const Point3& v : mesh.vertices) {
        // North-up rasters here: invert the axis-aligned transform, then confirm exactly.
        const double col = std::floor((v.x - gt[0]) / gt[1]);
        const double row = std::floor((v.y - gt[3]) / gt[5]);
        const bool inside = col >= 0 && row >= 0 && col < raster.width && row < raster.height;
        const std::size_t i =
            inside ? static_cast<std::size_t>(row) * static_cast<std::size_t>(raster.width) +
                         static_cast<std::size_t>(col)
                   : 0;
        const bool exact = inside && raster.valid[i] != 0 &&
                           v.x == gt[0] + (col + 0.5) * gt[1] + (row + 0.5) * gt[2] &&
                           v.y == gt[3] + (col + 0.5) * gt[4] + (row + 0.5) * gt[5] &&
                           v.z == raster.values[i];
        wrong += exact ? 0 : 1;
    }
    EXPECT_EQ(wrong, 0U) << "vertices that are not a valid cell centre with its exact value";
    test::expectExactDelaunayOf(mesh, raster.validCentres);
}

TEST(BuildPipeline, WritesExactTin_ForStormLakeWithNodataEdges) {
    expectTinOfValidCells(sharedDem("gdalraster__storml_elev_orig.tif"), "UTM zone 12N");
}

TEST(BuildPipeline, WritesExactTin_ForMountHood) {
    expectTinOfValidCells(sharedDem("gdalraster__lf_elev_220_mt_hood_utm.tif"), "UTM zone 10N");
}

TEST(BuildPipeline, WritesExactTin_ForBundledSample) {
    expectTinOfValidCells(fs::path(TERRATIN_SAMPLE_DEMS) / "ridges_utm.tif", "UTM zone 33N");
}

TEST(BuildPipeline, RefusesExistingOutput_BeforeReading) {
    TemporaryDirectory directory;
    BuildOptions options;
    options.inputs = {(fs::path(TERRATIN_SAMPLE_DEMS) / "ridges_utm.tif").string()};
    options.output = directory.path() / "tin.gpkg";
    std::ofstream(options.output) << "keep me";
    EXPECT_THROW(runBuild(options), InvalidInputError);
    std::ifstream kept(options.output);
    std::string content;
    std::getline(kept, content);
    EXPECT_EQ(content, "keep me");
}

// The simplification's report once gave the refiner's mesh bytes as history bytes, a history
// the refiner does not keep.
TEST(BuildPipeline, SimplificationReportsMeshBytes_NotHistoryBytes) {
    TemporaryDirectory directory;
    BuildOptions options;
    options.inputs = {(fs::path(TERRATIN_SAMPLE_DEMS) / "ridges_utm.tif").string()};
    options.output = directory.path() / "tin.ply";
    options.refine = RefineOptions{};
    options.refine->maxError = 1.0;
    const BuildReport report = runBuild(options);
    EXPECT_EQ(report.historyBytesPerPoint, 0.0);
    EXPECT_GT(report.meshBytesPerPoint, 0.0);
    EXPECT_NE(toJson(report).find("\"mesh_bytes_per_point\": "), std::string::npos);
}

TEST(BuildPipeline, ReportsJsonWithCountsAndTimings) {
    BuildReport report;
    report.points = 12;
    report.triangles = 20;
    report.input = "a \"quoted\" name.tif";
    const std::string json = toJson(report);
    EXPECT_NE(json.find("\"counts\": {"), std::string::npos);
    EXPECT_NE(json.find("\"points\": 12"), std::string::npos);
    EXPECT_NE(json.find("\"triangles\": 20"), std::string::npos);
    EXPECT_NE(json.find("\"timings\": {\"read\": "), std::string::npos);
    EXPECT_NE(json.find("a \\\"quoted\\\" name.tif"), std::string::npos);
}

} // namespace
} // namespace terratin

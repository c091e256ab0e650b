// runBuild with point clouds and coordinate systems, checked from the written file: mixed
// inputs merged in one CRS, --t_srs, geographic input projected to its UTM zone with exact
// elevations, --z-factor, and the errors of a run that lacks a CRS.

#include "terratin/pipeline/build_pipeline.hpp"

#include "las_test_file.hpp"
#include "terratin/crs/reprojection.hpp"
#include "terratin/error.hpp"

#include <gdal_priv.h>
#include <gdal_utils.h>
#include <ogrsf_frmts.h>

#include "temporary_directory.hpp"

#include <gtest/gtest.h>

#include <GeographicLib/UTMUPS.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <vector>

namespace terratin {
namespace {

namespace fs = std::filesystem;

const std::string kSample = std::string(TERRATIN_SAMPLE_DEMS) + "/ridges_utm.tif";
using TempDir = test::TemporaryDirectory;

struct WrittenTin {
    std::vector<Point3> vertices; // distinct, in first-seen order
    std::size_t triangles = 0;
    std::string crsWkt;
};

WrittenTin readTin(const fs::path& path) {
    WrittenTin tin;
    std::unique_ptr<GDALDataset> dataset(
        GDALDataset::Open(path.c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY));
    EXPECT_NE(dataset, nullptr);
    if (!dataset)
        return tin;
    OGRLayer* layer = dataset->GetLayer(0);
    if (const OGRSpatialReference* srs = layer->GetSpatialRef()) {
        char* wkt = nullptr;
        srs->exportToWkt(&wkt);
        tin.crsWkt = wkt;
        CPLFree(wkt);
    }
    std::set<std::pair<double, double>> seen;
    for (const auto& feature : *layer) {
        ++tin.triangles;
        const OGRLinearRing* ring = feature->GetGeometryRef()->toPolygon()->getExteriorRing();
        for (int i = 0; i < 3; ++i)
            if (seen.emplace(ring->getX(i), ring->getY(i)).second)
                tin.vertices.push_back({ring->getX(i), ring->getY(i), ring->getZ(i)});
    }
    return tin;
}

BuildOptions optionsFor(const std::vector<std::string>& inputs, const fs::path& output) {
    BuildOptions options;
    options.inputs = inputs;
    options.output = output;
    options.validate = true;
    return options;
}

/// A small piece of a raster (gdal_translate -srcwin), so tests stay fast.
void cutWindow(const std::string& source, const fs::path& target, int col, int row, int width,
               int height) {
    std::unique_ptr<GDALDataset> in(GDALDataset::Open(source.c_str(), GDAL_OF_RASTER));
    ASSERT_NE(in, nullptr);
    const std::string args[] = {"-srcwin",
                                std::to_string(col),
                                std::to_string(row),
                                std::to_string(width),
                                std::to_string(height),
                                "-of",
                                "GTiff"};
    std::vector<char*> argv;
    for (const std::string& arg : args)
        argv.push_back(const_cast<char*>(arg.c_str()));
    argv.push_back(nullptr);
    GDALTranslateOptions* options = GDALTranslateOptionsNew(argv.data(), nullptr);
    GDALDatasetH out = GDALTranslate(target.c_str(), in.get(), options, nullptr);
    GDALTranslateOptionsFree(options);
    ASSERT_NE(out, nullptr);
    GDALClose(out);
}

/// 40 x 40 cells of the bundled sample (UTM 33N, 10 m), cells 90..129: x from 455900 to
/// 456300, y from 5104100 down to 5103700. Small enough for tests under the sanitizers.
fs::path smallSample(const TempDir& dir) {
    GDALAllRegister();
    const fs::path window = dir.file("sample_window.tif");
    cutWindow(kSample, window, 90, 90, 40, 40);
    return window;
}

TEST(PointCloudPipeline, ProjectsSrtmWindowToUtm19_WithExactElevations) {
    const fs::path tile = fs::path(TERRATIN_SHARED_DEMS) / "srtmpy__N44W072" / "N44W072.hgt";
    if (!fs::exists(tile))
        GTEST_SKIP() << tile << " not available";
    GDALAllRegister();
    TempDir dir;
    const fs::path window = dir.file("window.tif");
    cutWindow(tile.string(), window, 500, 600, 60, 50);

    // The window's cells, read independently: (lon, lat) -> elevation.
    std::unique_ptr<GDALDataset> raster(GDALDataset::Open(window.c_str(), GDAL_OF_RASTER));
    ASSERT_NE(raster, nullptr);
    double gt[6];
    raster->GetGeoTransform(gt);
    std::vector<double> values(60 * 50);
    ASSERT_EQ(raster->GetRasterBand(1)->RasterIO(GF_Read, 0, 0, 60, 50, values.data(), 60, 50,
                                                 GDT_Float64, 0, 0),
              CE_None);

    std::vector<std::string> notices;
    BuildOptions options = optionsFor({window.string()}, dir.file("tin.gpkg"));
    options.notice = [&](std::string_view text) { notices.emplace_back(text); };
    const BuildReport report = runBuild(options);
    EXPECT_TRUE(report.validated);
    EXPECT_EQ(report.zone, "UTM zone 19N");
    EXPECT_EQ(report.crsCode, "EPSG:32619");
    EXPECT_EQ(report.sourceCrsCode, "EPSG:4326");
    EXPECT_TRUE(report.reprojected);
    ASSERT_EQ(notices.size(), 1U);
    EXPECT_NE(notices[0].find("UTM zone 19N"), std::string::npos);
    EXPECT_EQ(report.notices, notices);

    const WrittenTin tin = readTin(options.output);
    EXPECT_EQ(crs::describeCrs(tin.crsWkt).code, "EPSG:32619");
    ASSERT_EQ(tin.vertices.size(), values.size());
    EXPECT_EQ(tin.triangles, report.triangles);
    // Every vertex: GeographicLib's UTM image of a cell centre (1 mm), with that cell's exact z.
    std::map<std::pair<long long, long long>, double> expected;
    for (int row = 0; row < 50; ++row)
        for (int col = 0; col < 60; ++col) {
            const double lon = gt[0] + (col + 0.5) * gt[1];
            const double lat = gt[3] + (row + 0.5) * gt[5];
            int zone = 0;
            bool north = false;
            double x = 0.0;
            double y = 0.0;
            GeographicLib::UTMUPS::Forward(lat, lon, zone, north, x, y, 19);
            expected[{std::llround(x * 100), std::llround(y * 100)}] =
                values[static_cast<std::size_t>(row) * 60 + static_cast<std::size_t>(col)];
        }
    std::size_t matched = 0;
    for (const Point3& v : tin.vertices) {
        // Rounded to the centimetre; the vertex is within 1 mm of the centre, so one of the
        // neighbouring keys holds it.
        for (long long dx = -1; dx <= 1; ++dx)
            for (long long dy = -1; dy <= 1; ++dy) {
                const auto it =
                    expected.find({std::llround(v.x * 100) + dx, std::llround(v.y * 100) + dy});
                if (it != expected.end() && v.z == it->second) {
                    ++matched;
                    dx = dy = 2;
                }
            }
    }
    EXPECT_EQ(matched, tin.vertices.size()) << "vertices not at a cell centre with its exact z";
}

TEST(PointCloudPipeline, ReprojectsToWebMercator_AndRoundTripsWithinAMillimetre) {
    TempDir dir;
    const fs::path sample = smallSample(dir);
    BuildOptions options = optionsFor({sample.string()}, dir.file("tin.gpkg"));
    options.targetSrs = "EPSG:3857";
    const BuildReport report = runBuild(options);
    EXPECT_EQ(report.crsCode, "EPSG:3857");
    EXPECT_TRUE(report.zone.empty());
    EXPECT_TRUE(report.reprojected);
    const WrittenTin tin = readTin(options.output);
    EXPECT_EQ(crs::describeCrs(tin.crsWkt).code, "EPSG:3857");

    // Back to UTM 33N: each vertex returns within 1 mm of a 10 m cell centre
    // (455905 + 10 col, 5104095 - 10 row), with the raster's z.
    std::unique_ptr<GDALDataset> raster(GDALDataset::Open(sample.c_str(), GDAL_OF_RASTER));
    ASSERT_NE(raster, nullptr);
    std::vector<double> values(40 * 40);
    ASSERT_EQ(raster->GetRasterBand(1)->RasterIO(GF_Read, 0, 0, 40, 40, values.data(), 40, 40,
                                                 GDT_Float64, 0, 0),
              CE_None);
    std::vector<Point3> back = tin.vertices;
    crs::Reprojector(tin.crsWkt, crs::crsFromUserInput("EPSG:32633", "test")).transform(back);
    ASSERT_EQ(back.size(), report.vertices);
    for (const Point3& p : back) {
        const double col = std::round((p.x - 455905.0) / 10.0);
        const double row = std::round((5104095.0 - p.y) / 10.0);
        ASSERT_TRUE(col >= 0 && col < 40 && row >= 0 && row < 40) << p.x << ", " << p.y;
        ASSERT_NEAR(p.x, 455905.0 + 10.0 * col, 1e-3);
        ASSERT_NEAR(p.y, 5104095.0 - 10.0 * row, 1e-3);
        ASSERT_EQ(p.z, values[static_cast<std::size_t>(row) * 40 + static_cast<std::size_t>(col)]);
    }
}

TEST(PointCloudPipeline, MergesRasterLasAndGeoJson_InTheRastersCrs) {
    TempDir dir;
    const fs::path sample = smallSample(dir);
    // LAS in EPSG:32633 with three points inside the sample's area (and one duplicate of a
    // cell centre), GeoJSON in WGS 84 with one point there too.
    test::LasTestFile las;
    las.scale = {0.01, 0.01, 0.01};
    las.points = {{45600312, 510400047, 100000, 1, 1, 2},
                  {45700001, 510300001, 120000, 1, 1, 2},
                  {45600500, 510399500, 99900, 1, 1, 2}, // the cell centre (456005, 5103995)
                  {45800000, 510200000, 50000, 1, 1, 1}};
    las.vlrs.push_back(test::geoKeysForProjectedEpsg(32633));
    const fs::path lasPath = dir.file("cloud.las");
    {
        const std::vector<std::byte> bytes = las.bytes();
        std::ofstream(lasPath, std::ios::binary)
            .write(reinterpret_cast<const char*>(bytes.data()),
                   static_cast<std::streamsize>(bytes.size()));
    }
    const Point2 spot = crs::Reprojector(crs::crsFromUserInput("EPSG:32633", "t"),
                                         crs::crsFromUserInput("EPSG:4326", "t"))
                            .transform(Point2{456789.0, 5103456.0});
    const fs::path json = dir.file("spot.geojson");
    std::ofstream(json) << R"({"type": "FeatureCollection", "features": [{"type": "Feature",
        "properties": {}, "geometry": {"type": "Point", "coordinates": [)"
                        << std::setprecision(17) << spot.x << ", " << spot.y << ", 777.5]}}]}";

    BuildOptions options =
        optionsFor({sample.string(), lasPath.string(), json.string()}, dir.file("tin.gpkg"));
    options.lasClasses = {2};
    const BuildReport report = runBuild(options);
    ASSERT_EQ(report.inputs.size(), 3U);
    EXPECT_EQ(report.inputs[0].kind, "raster");
    EXPECT_EQ(report.inputs[1].kind, "las");
    EXPECT_EQ(report.inputs[1].records, 4U);
    EXPECT_EQ(report.inputs[1].filteredOut, 1U);
    EXPECT_EQ(report.inputs[1].points, 3U);
    EXPECT_EQ(report.inputs[1].duplicates, 1U); // the cell centre already given by the raster
    EXPECT_FALSE(report.inputs[1].reprojected);
    EXPECT_EQ(report.inputs[2].kind, "vector");
    EXPECT_TRUE(report.inputs[2].reprojected);
    EXPECT_EQ(report.crsCode, "EPSG:32633");
    EXPECT_EQ(report.sourceCrsName, "several");
    EXPECT_EQ(report.points, report.inputs[0].points + 4U);
    EXPECT_EQ(report.duplicates, 1U);
    EXPECT_EQ(report.vertices, report.points - 1U);

    const WrittenTin tin = readTin(options.output);
    ASSERT_EQ(tin.vertices.size(), report.vertices);
    const auto has = [&](double x, double y, double z, double tolerance) {
        return std::any_of(tin.vertices.begin(), tin.vertices.end(), [&](const Point3& v) {
            return std::abs(v.x - x) <= tolerance && std::abs(v.y - y) <= tolerance && v.z == z;
        });
    };
    EXPECT_TRUE(has(456003.12, 5104000.47, 1000.0, 0.0));
    EXPECT_TRUE(has(457000.01, 5103000.01, 1200.0, 0.0));
    EXPECT_TRUE(has(456789.0, 5103456.0, 777.5, 1e-3));
    EXPECT_FALSE(has(458000.0, 5102000.0, 500.0, 0.0)); // class 1: filtered out
}

TEST(PointCloudPipeline, DemandsSourceSrs_WhenAnInputHasNoCrs) {
    TempDir dir;
    const fs::path sample = smallSample(dir);
    const fs::path text = dir.file("spots.xyz");
    std::ofstream(text) << "456003 5104000 100\n456100 5104100 101\n456200 5104000 99\n";
    // Alone and without --t_srs: no CRS needed, none written.
    BuildReport report = runBuild(optionsFor({text.string()}, dir.file("alone.gpkg")));
    EXPECT_TRUE(report.crsName.empty());

    // Beside a raster with a CRS, or with --t_srs: an error naming the file and the source CRS
    // option, spelled as the caller spells options.
    for (const bool withTarget : {false, true}) {
        for (const OptionSpelling spelling :
             {OptionSpelling::Keyword, OptionSpelling::CommandLine}) {
            BuildOptions options =
                withTarget ? optionsFor({text.string()}, dir.file("t.gpkg"))
                           : optionsFor({sample.string(), text.string()}, dir.file("m.gpkg"));
            if (withTarget)
                options.targetSrs = "EPSG:3857";
            options.optionSpelling = spelling;
            const std::string sourceOption =
                spelling == OptionSpelling::CommandLine ? "with --s_srs" : "with s_srs";
            try {
                runBuild(options);
                FAIL() << "an input without CRS was accepted";
            } catch (const CrsError& error) {
                EXPECT_NE(std::string(error.what()).find("spots.xyz"), std::string::npos);
                EXPECT_NE(std::string(error.what()).find(sourceOption), std::string::npos)
                    << error.what();
            }
            EXPECT_FALSE(fs::exists(options.output));
        }
    }

    // --s_srs supplies it.
    BuildOptions options = optionsFor({sample.string(), text.string()}, dir.file("s.gpkg"));
    options.sourceSrs = "EPSG:32633";
    report = runBuild(options);
    EXPECT_EQ(report.crsCode, "EPSG:32633");
    EXPECT_EQ(report.points, report.inputs[0].points + 3U);
}

// The readers' and the writer's messages, reached through runBuild, name options the
// way its caller does: "--columns" for the command line, "columns" for a keyword caller.
TEST(PointCloudPipeline, ReaderAndWriterMessagesNameOptionsAsTheCallerDoes) {
    TempDir dir;
    const fs::path text = dir.file("spots.xyz");
    std::ofstream(text) << "456003 5104000 100\n456100 5104100 101\n456200 5104000 99\n";
    const fs::path flat = dir.file("flat.geojson");
    std::ofstream(flat) << R"({"type": "FeatureCollection", "features": [
      {"type": "Feature", "properties": {"h": 1}, "geometry": {"type": "Point", "coordinates": [1, 2]}}
    ]})";
    const fs::path appendTo = dir.file("layers.gpkg");
    runBuild(optionsFor({text.string()}, appendTo));

    struct Case {
        BuildOptions options;
        std::string commandLine;
        std::string keyword;
    };
    std::vector<Case> cases;
    cases.push_back({optionsFor({text.string()}, dir.file("columns.gpkg")),
                     "no header line to find the columns named in --columns (the first line",
                     "no header line to find the columns named in columns (the first line"});
    cases.back().options.textColumns = {"x", "y", "z"};
    cases.push_back({optionsFor({flat.string()}, dir.file("flat.gpkg")),
                     "its points have no z; name the elevation attribute with --z-field",
                     "its points have no z; name the elevation attribute with z_field"});
    cases.push_back({optionsFor({text.string()}, appendTo),
                     "already has a layer 'tin'; choose another --layer or use --overwrite",
                     "already has a layer 'tin'; choose another layer or use overwrite"});
    cases.back().options.appendLayer = true;

    for (Case& c : cases) {
        for (const OptionSpelling spelling :
             {OptionSpelling::CommandLine, OptionSpelling::Keyword}) {
            c.options.optionSpelling = spelling;
            const std::string& expected =
                spelling == OptionSpelling::CommandLine ? c.commandLine : c.keyword;
            try {
                runBuild(c.options);
                ADD_FAILURE() << "no error for " << expected;
            } catch (const InvalidInputError& error) {
                EXPECT_NE(std::string(error.what()).find(expected), std::string::npos)
                    << error.what();
            }
        }
    }
}

TEST(PointCloudPipeline, ScalesElevationsByZFactor_AndKeepsGeographicWhenAsked) {
    TempDir dir;
    const fs::path text = dir.file("spots.csv");
    std::ofstream(text) << "lon,lat,elev_ft\n-71.5,44.5,1000\n-71.4,44.5,2000\n-71.45,44.6,3000\n";
    std::ofstream(dir.file("spots.prj")) << crs::crsFromUserInput("EPSG:4326", "test");
    BuildOptions options = optionsFor({text.string()}, dir.file("deg.gpkg"));
    options.keepGeographic = true;
    options.zFactor = 0.3048;
    const BuildReport report = runBuild(options);
    EXPECT_EQ(report.crsCode, "EPSG:4326");
    EXPECT_TRUE(report.zone.empty());
    EXPECT_FALSE(report.reprojected);
    const WrittenTin tin = readTin(options.output);
    std::multiset<double> zs;
    for (const Point3& v : tin.vertices) {
        zs.insert(v.z);
        EXPECT_GE(v.x, -71.5); // still degrees
        EXPECT_LE(v.y, 44.6);
    }
    EXPECT_EQ(zs, (std::multiset<double>{1000 * 0.3048, 2000 * 0.3048, 3000 * 0.3048}));

    options.zFactor = 0.0;
    options.output = dir.file("zero.gpkg");
    EXPECT_THROW(runBuild(options), InvalidInputError);
}

TEST(PointCloudPipeline, GroundOfAutzen_StaysInOregonLambertFeet) {
    const fs::path autzen = fs::path(TERRATIN_SHARED_DEMS) / "pdal__autzen_trim.las";
    if (!fs::exists(autzen))
        GTEST_SKIP() << autzen << " not available";
    TempDir dir;
    BuildOptions options = optionsFor({autzen.string()}, dir.file("autzen.gpkg"));
    options.lasClasses = {2};
    const BuildReport report = runBuild(options);
    EXPECT_EQ(report.points, 26107U);
    EXPECT_EQ(report.filteredOut, 110000U - 26107U);
    EXPECT_FALSE(report.reprojected);
    const crs::CrsDescription description = crs::describeCrs(readTin(options.output).crsWkt);
    EXPECT_TRUE(description.projected);
    EXPECT_NEAR(description.metresPerUnit, 0.3048, 1e-6);
    EXPECT_NE(description.name.find("Lambert"), std::string::npos);
}

TEST(PointCloudPipeline, ReportsInputsAndCrsInJson) {
    BuildReport report;
    report.crsName = "WGS 84 / UTM zone 19N";
    report.crsCode = "EPSG:32619";
    report.sourceCrsName = "WGS 84";
    report.sourceCrsCode = "EPSG:4326";
    report.zone = "UTM zone 19N";
    report.reprojected = true;
    report.zFactor = 0.3048;
    InputReport input;
    input.path = "a.las";
    input.kind = "las";
    input.records = 10;
    input.filteredOut = 4;
    input.points = 6;
    input.duplicates = 1;
    report.inputs.push_back(input);
    report.notices.push_back("projecting");
    const std::string json = toJson(report);
    for (const char* key :
         {"\"source_crs\": {\"name\": \"WGS 84\", \"code\": \"EPSG:4326\"}",
          "\"target_crs\": {\"name\": \"WGS 84 / UTM zone 19N\", \"code\": \"EPSG:32619\"}",
          "\"zone\": \"UTM zone 19N\"", "\"z_factor\": 0.3048", "\"records\": 10",
          "\"filtered_out\": 4", "\"duplicates\": 1", "\"notices\": [\"projecting\"]",
          "\"reprojected\": true"})
        EXPECT_NE(json.find(key), std::string::npos) << key << " missing in " << json;
    const std::string text = toInputSummary(report);
    EXPECT_NE(
        text.find(
            "input 1: a.las (las, no CRS): 10 records, 4 filtered out, 6 points, 1 duplicates"),
        std::string::npos)
        << text;
    EXPECT_NE(text.find("WGS 84 [EPSG:4326] -> WGS 84 / UTM zone 19N [EPSG:32619] (UTM zone 19N"),
              std::string::npos)
        << text;
}

} // namespace
} // namespace terratin

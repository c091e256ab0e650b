// runBuild with --breaklines on the bundled sample DEM, checked from the written PLY: every
// breakline segment inside the data is an edge (or a chain of edges) of the TIN, the TIN is
// exactly constrained Delaunay (validate), and lines outside the data are clipped with a
// notice.

#include "terratin/pipeline/build_pipeline.hpp"

#include "constraint_test_data.hpp"
#include "mesh_invariants.hpp"
#include "mesh_readers.hpp"
#include "terratin/error.hpp"
#include "terratin/gdal_error.hpp"

#include <gdal_priv.h>
#include <ogr_spatialref.h>
#include <ogrsf_frmts.h>

#include "temporary_directory.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iterator>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

namespace terratin {
namespace {

namespace fs = std::filesystem;
using test::TemporaryDirectory;

const fs::path kSample = fs::path(TERRATIN_SAMPLE_DEMS) / "ridges_utm.tif";

/// Lines over the sample (cell centres 455005..458195 x 5102605..5104995, EPSG:32633) at
/// positions off the cell grid, so that each segment is one edge unless another line crosses
/// it. `epsg` 0: no CRS.
void writeLines(const fs::path& path, const std::vector<std::string>& wkts, int epsg = 32633) {
    test::writeVectorLayer(path, "lines", wkts, epsg);
}

BuildOptions optionsFor(const fs::path& lines, const fs::path& output) {
    BuildOptions options;
    options.inputs = {kSample.string()};
    options.output = output;
    options.breaklines = {lines.string()};
    options.validate = true;
    return options;
}

using Edge = std::pair<std::uint32_t, std::uint32_t>;

struct ReadTin {
    test::ReadMesh mesh;
    std::set<Edge> edges;
    std::map<std::pair<double, double>, std::uint32_t> vertexAt;
};

ReadTin readTin(const fs::path& path) {
    ReadTin tin{test::readPly(path), {}, {}};
    for (std::size_t t = 0; t < tin.mesh.triangles.size(); t += 3)
        for (std::size_t i = 0; i < 3; ++i) {
            const std::uint32_t a = tin.mesh.triangles[t + i];
            const std::uint32_t b = tin.mesh.triangles[t + (i + 1) % 3];
            tin.edges.insert({std::min(a, b), std::max(a, b)});
        }
    for (std::uint32_t v = 0; v < tin.mesh.vertices.size(); ++v)
        tin.vertexAt[{tin.mesh.vertices[v].x, tin.mesh.vertices[v].y}] = v;
    return tin;
}

/// Whether the TIN has an edge between the vertices at (x, y) of `a` and `b`.
bool hasEdge(const ReadTin& tin, Point2 a, Point2 b) {
    const auto from = tin.vertexAt.find({a.x, a.y});
    const auto to = tin.vertexAt.find({b.x, b.y});
    if (from == tin.vertexAt.end() || to == tin.vertexAt.end())
        return false;
    return tin.edges.count(
               {std::min(from->second, to->second), std::max(from->second, to->second)}) == 1;
}

TEST(BreaklinesPipeline, EverySegmentIsAnEdgeOfTheTin_WithLineZOrTheSurface) {
    TemporaryDirectory directory;
    const fs::path lines = directory.path() / "lines.gpkg";
    writeLines(lines, {"LINESTRING Z (455501.3 5104003.7 500, 456700.9 5103100.2 501, "
                       "457800.1 5104500.3 502)",
                       "LINESTRING (455300.7 5102700.1, 456000.3 5102900.9)"});
    const BuildReport report = runBuild(optionsFor(lines, directory.path() / "tin.ply"));
    EXPECT_TRUE(report.validated);
    EXPECT_EQ(report.breaklines, 2U);
    EXPECT_EQ(report.clippedBreaklines, 0U);
    EXPECT_EQ(report.constraintVertices, 5U);
    EXPECT_EQ(report.constraintCrossings, 0U);
    EXPECT_EQ(report.vertices, report.points + 5);

    const ReadTin tin = readTin(directory.path() / "tin.ply");
    EXPECT_TRUE(hasEdge(tin, {455501.3, 5104003.7}, {456700.9, 5103100.2}));
    EXPECT_TRUE(hasEdge(tin, {456700.9, 5103100.2}, {457800.1, 5104500.3}));
    EXPECT_TRUE(hasEdge(tin, {455300.7, 5102700.1}, {456000.3, 5102900.9}));
    // The 3D line keeps its z; the 2D one takes the surface's, between its neighbours'.
    EXPECT_EQ(tin.mesh.vertices[tin.vertexAt.at({456700.9, 5103100.2})].z, 501.0);
    const double surface = tin.mesh.vertices[tin.vertexAt.at({455300.7, 5102700.1})].z;
    EXPECT_TRUE(std::isfinite(surface));
    EXPECT_NE(surface, 0.0);
}

const std::vector<std::string> kTwoLines{
    "LINESTRING Z (455501.3 5104003.7 500, 456700.9 5103100.2 501, 457800.1 5104500.3 502)",
    "LINESTRING (455300.7 5102700.1, 456000.3 5102900.9)"};

TEST(BreaklinesPipeline, GeoPackageEdgesSayWhichAreConstrained_AndLandXmlListsTheBreaklines) {
    TemporaryDirectory directory;
    const fs::path lines = directory.path() / "lines.gpkg";
    writeLines(lines, kTwoLines);
    BuildOptions options = optionsFor(lines, directory.path() / "tin.gpkg");
    options.edges = true;
    (void)runBuild(options);
    std::unique_ptr<GDALDataset> dataset(GDALDataset::Open((directory.path() / "tin.gpkg").c_str(),
                                                           GDAL_OF_VECTOR | GDAL_OF_READONLY));
    ASSERT_NE(dataset, nullptr);
    OGRLayer* edges = dataset->GetLayerByName("edges");
    ASSERT_NE(edges, nullptr);
    edges->SetAttributeFilter("constrained = 1");
    EXPECT_EQ(edges->GetFeatureCount(), 3); // the three segments, each one edge
    edges->SetAttributeFilter("constrained = 0");
    EXPECT_GT(edges->GetFeatureCount(), 200000);

    options = optionsFor(lines, directory.path() / "tin.xml");
    (void)runBuild(options);
    std::ifstream xml(directory.path() / "tin.xml");
    const std::string text((std::istreambuf_iterator<char>(xml)), std::istreambuf_iterator<char>());
    EXPECT_NE(text.find("<Breakline brkType=\"standard\">\n<PntList3D>5104003.7 455501.3 500 "
                        "5103100.2 456700.9 501 5104500.3 457800.1 502</PntList3D>"),
              std::string::npos);
    std::size_t breaklines = 0;
    for (std::size_t at = text.find("<Breakline "); at != std::string::npos;
         at = text.find("<Breakline ", at + 1))
        ++breaklines;
    EXPECT_EQ(breaklines, 2U);
    EXPECT_LT(text.find("</SourceData>"), text.find("<Definition"));
}

TEST(BreaklinesPipeline, EveryMethodAndThreadCountGivesTheSameTin) {
    // A DEM's cells are cocircular four by four; the triangulators break those ties by the
    // points' coordinates alone, so the full-resolution TIN does not depend on the method, the
    // number of strips or the order of insertion.
    TemporaryDirectory directory;
    const fs::path lines = directory.path() / "lines.gpkg";
    writeLines(lines, {"LINESTRING (455300.7 5102900.1, 458000.3 5104900.9)",
                       "LINESTRING (455501.3 5104803.7, 457900.9 5102700.2)"});
    std::vector<ReadTin> tins;
    for (const TriangulationMethod method :
         {TriangulationMethod::Sequential, TriangulationMethod::Batch,
          TriangulationMethod::Circumcircle, TriangulationMethod::Strips})
        for (const unsigned threads : {1U, 2U}) {
            BuildOptions options = optionsFor(lines, directory.path() / "tin.ply");
            options.overwrite = true;
            options.triangulation.method = method;
            options.triangulation.threads = threads;
            EXPECT_TRUE(runBuild(options).validated);
            tins.push_back(readTin(directory.path() / "tin.ply"));
        }
    auto trianglesOf = [](const ReadTin& tin) {
        return test::sortedTriangles(tin.mesh.vertices, tin.mesh.triangles);
    };
    const std::vector<test::CornerTriple> first = trianglesOf(tins[0]);
    for (std::size_t i = 1; i < tins.size(); ++i)
        EXPECT_TRUE(trianglesOf(tins[i]) == first) << "build " << i;
    // The four ends and the crossing are the added vertices.
    std::vector<Point2> added;
    for (const auto& [place, v] : tins[0].vertexAt)
        if (std::fmod(place.first - 5.0, 10.0) != 0.0 || std::fmod(place.second - 5.0, 10.0) != 0.0)
            added.push_back({place.first, place.second});
    ASSERT_EQ(added.size(), 5U);
}

TEST(BreaklinesPipeline, APointCloudTakesBreaklines_WithZFromItsTin) {
    // Scattered points of the plane z = x / 100 + y / 50 (text, no CRS: the lines have none
    // either); a breakline's vertices get the TIN's z, exact on a plane up to rounding.
    TemporaryDirectory directory;
    const fs::path points = directory.path() / "points.xyz";
    (void)test::writePlanePoints(points, 2000, 12345);
    const fs::path lines = directory.path() / "lines.gpkg";
    writeLines(lines, {"LINESTRING (100.25 200.5, 800.75 650.125, 300.5 900.25)"}, 0);
    BuildOptions options;
    options.inputs = {points.string()};
    options.output = directory.path() / "tin.ply";
    options.breaklines = {lines.string()};
    options.validate = true;
    const BuildReport report = runBuild(options);
    EXPECT_TRUE(report.validated);
    EXPECT_EQ(report.breaklines, 1U);
    const ReadTin tin = readTin(directory.path() / "tin.ply");
    EXPECT_TRUE(hasEdge(tin, {100.25, 200.5}, {800.75, 650.125}));
    EXPECT_TRUE(hasEdge(tin, {800.75, 650.125}, {300.5, 900.25}));
    const Point3& corner = tin.mesh.vertices[tin.vertexAt.at({800.75, 650.125})];
    EXPECT_NEAR(corner.z, 800.75 / 100.0 + 650.125 / 50.0, 1e-9);
}

TEST(BreaklinesPipeline, APointCloudsBreaklineZ_IsTheSameBitsForEveryThreadCount) {
    // Regression: the breakline vertices' z from the TIN followed the numbering of its
    // triangles, which differs with the threads that built it (TinLocator::elevationIn), so
    // the TIN differed in the last bits of some z between 1 and 2 threads.
    TemporaryDirectory directory;
    const fs::path points = directory.path() / "points.xyz";
    (void)test::writePlanePoints(points, 20000, 777);
    const fs::path lines = directory.path() / "lines.gpkg";
    std::vector<std::string> wkts;
    for (int k = 0; k < 40; ++k) {
        const double y = 12.5 + 24.25 * k;
        wkts.push_back("LINESTRING (3.5 " + std::to_string(y) + ", 500.25 " +
                       std::to_string(y + 300.0 - 11.0 * k) + ", 996.75 " +
                       std::to_string(990.0 - y) + ")");
    }
    writeLines(lines, wkts, 0);
    std::vector<std::vector<Point3>> vertices;
    for (const unsigned threads : {1U, 2U}) {
        BuildOptions options;
        options.inputs = {points.string()};
        options.output = directory.path() / "tin.ply";
        options.overwrite = true;
        options.breaklines = {lines.string()};
        options.triangulation.threads = threads;
        EXPECT_EQ(runBuild(options).breaklines, 40U);
        vertices.push_back(readTin(directory.path() / "tin.ply").mesh.vertices);
        std::sort(vertices.back().begin(), vertices.back().end(),
                  [](const Point3& a, const Point3& b) {
                      return std::tie(a.x, a.y, a.z) < std::tie(b.x, b.y, b.z);
                  });
    }
    ASSERT_EQ(vertices[0].size(), vertices[1].size());
    EXPECT_GT(vertices[0].size(), 20000U);
    std::size_t differing = 0;
    for (std::size_t v = 0; v < vertices[0].size(); ++v)
        differing += vertices[0][v] == vertices[1][v] ? 0 : 1;
    EXPECT_EQ(differing, 0U);
}

/// Twice the planimetric area of the TIN in `path` (a PLY).
double twiceTinArea(const fs::path& path) {
    const test::ReadMesh mesh = test::readPly(path);
    double area = 0.0;
    for (std::size_t t = 0; t < mesh.triangles.size(); t += 3) {
        const Point3& a = mesh.vertices[mesh.triangles[t]];
        const Point3& b = mesh.vertices[mesh.triangles[t + 1]];
        const Point3& c = mesh.vertices[mesh.triangles[t + 2]];
        area += (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
    }
    return area;
}

// A pentagon inside the sample's data, off the cell grid: twice its area by the shoelace.
const char* const kPentagon = "POLYGON ((455600.5 5103000.25, 457200.75 5102800.5, "
                              "457900.25 5103900.75, 456500.5 5104700.25, 455300.25 5104100.5, "
                              "455600.5 5103000.25))";
double twicePentagonArea() {
    const double x[] = {455600.5, 457200.75, 457900.25, 456500.5, 455300.25};
    const double y[] = {5103000.25, 5102800.5, 5103900.75, 5104700.25, 5104100.5};
    double area = 0.0;
    for (int i = 0; i < 5; ++i)
        area += x[i] * y[(i + 1) % 5] - x[(i + 1) % 5] * y[i];
    return area;
}

TEST(ConstraintAreas, ClipKeepsExactlyThePolygon_AndEraseCutsItOut) {
    TemporaryDirectory directory;
    const fs::path area = directory.path() / "area.gpkg";
    writeLines(area, {kPentagon});
    BuildOptions options;
    options.inputs = {kSample.string()};
    options.validate = true;

    options.output = directory.path() / "whole.ply";
    (void)runBuild(options);
    const double whole = twiceTinArea(options.output);

    options.clip = area.string();
    options.output = directory.path() / "clipped.ply";
    const BuildReport clipped = runBuild(options);
    EXPECT_TRUE(clipped.validated);
    EXPECT_GT(clipped.areaTriangles, 0U);
    EXPECT_NEAR(twiceTinArea(options.output), twicePentagonArea(), 1e-6 * twicePentagonArea());

    options.clip.clear();
    options.erase = area.string();
    options.output = directory.path() / "erased.ply";
    (void)runBuild(options);
    EXPECT_NEAR(twiceTinArea(options.output), whole - twicePentagonArea(), 1e-6 * whole);
}

/// A TIN's planimetric area and where its triangles lie against a ring: by their centroids
/// (insideRing), which for a triangle wholly inside the ring is inside.
struct TinAgainstRing {
    double area = 0.0;
    std::size_t centroidsInside = 0;
    std::size_t triangles = 0;
};

TinAgainstRing tinAgainstRing(const fs::path& ply, const std::vector<Point2>& ring) {
    const test::ReadMesh mesh = test::readPly(ply);
    TinAgainstRing result;
    for (std::size_t t = 0; t < mesh.triangles.size(); t += 3) {
        const Point3& a = mesh.vertices[mesh.triangles[t]];
        const Point3& b = mesh.vertices[mesh.triangles[t + 1]];
        const Point3& c = mesh.vertices[mesh.triangles[t + 2]];
        result.area += 0.5 * ((b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x));
        const Point2 centroid{(a.x + b.x + c.x) / 3.0, (a.y + b.y + c.y) / 3.0};
        result.centroidsInside += test::insideRing(ring, centroid) ? 1 : 0;
        ++result.triangles;
    }
    return result;
}

/// 48 x 36 cells of 10 m whose lower left corner is no data below a staircase: the valid cells
/// (column c, s = 35 - row) are those with 3c + 7s >= 60, so the data's convex hull runs along
/// the slanted line through the cells (20, 0), (13, 3) and (6, 6). Cell (c, s) is centred at
/// (x0 + 5 + 10c, y0 - 355 + 10s).
void writeSlantedDem(const fs::path& path, double x0 = 500000.0, double y0 = 5000360.0) {
    std::vector<float> z;
    for (int row = 0; row < 36; ++row)
        for (int column = 0; column < 48; ++column)
            z.push_back(3 * column + 7 * (35 - row) >= 60
                            ? static_cast<float>(100 + column - row)
                            : std::numeric_limits<float>::quiet_NaN());
    test::writeElevations(path, 48, 36, x0, y0, 10.0, std::move(z));
}

/// A rectangle half outside that DEM's data: its sides cross the slanted part of the hull.
const std::vector<Point2> kAcrossTheSlant{
    {500128.3, 4999983.1}, {500201.7, 4999983.1}, {500201.7, 5000046.9}, {500128.3, 5000046.9}};

/// Builds `dem` with `ring` as clip and as erase area (simplified to maxError when given), and
/// checks each TIN against the overlap of the ring and the data's hull computed by GEOS: the
/// clipped TIN is that overlap, the erased one the hull without it, with no triangle inside.
void expectClipAndEraseCutTheOverlap(const fs::path& dem, const std::vector<Point2>& ring,
                                     std::optional<double> maxError = std::nullopt) {
    TemporaryDirectory directory;
    const fs::path area = directory.path() / "area.gpkg";
    test::writeVectorLayer(area, "area", {test::polygonWkt(ring)}, 0); // in the DEM's CRS
    const test::HullOverlap expected = test::hullOverlap(test::validCellCentres(dem), ring);
    ASSERT_GT(expected.overlap, 0.0);
    ASSERT_LT(expected.overlap, expected.hull);
    BuildOptions options;
    options.inputs = {dem.string()};
    options.validate = true;
    if (maxError) {
        options.refine.emplace();
        options.refine->maxError = *maxError;
    }

    options.erase = area.string();
    options.output = directory.path() / "erased.ply";
    (void)runBuild(options);
    const TinAgainstRing erased = tinAgainstRing(options.output, ring);
    EXPECT_EQ(erased.centroidsInside, 0U) << "triangles left inside the erase area";
    EXPECT_NEAR(erased.area, expected.hull - expected.overlap, 1e-9 * expected.hull);

    options.erase.clear();
    options.clip = area.string();
    options.output = directory.path() / "clipped.ply";
    const BuildReport clipped = runBuild(options);
    EXPECT_GT(clipped.areaTriangles, 0U);
    const TinAgainstRing kept = tinAgainstRing(options.output, ring);
    EXPECT_EQ(kept.centroidsInside, kept.triangles) << "triangles kept outside the clip area";
    EXPECT_NEAR(kept.area, expected.overlap, 1e-9 * expected.hull);
}

// A polygon that leaves the data through a slanted hull edge is cut off there a few ulps inside
// the hull; the TIN's region inside it once leaked round that end of its boundary into the rest:
// erase then dropped nothing and clip everything.
TEST(ConstraintAreas, ClipAndEraseAcrossASlantedHullEdge_CutExactlyTheOverlapWithTheHull) {
    TemporaryDirectory directory;
    const fs::path dem = directory.path() / "slanted.tif";
    writeSlantedDem(dem);
    expectClipAndEraseCutTheOverlap(dem, kAcrossTheSlant);
}

TEST(ConstraintAreas, ClipAndEraseAcrossASlantedHullEdge_CutExactlyTheOverlap_WhenSimplified) {
    TemporaryDirectory directory;
    const fs::path dem = directory.path() / "slanted.tif";
    writeSlantedDem(dem);
    expectClipAndEraseCutTheOverlap(dem, kAcrossTheSlant, 0.5);
}

// Sides along the cell centres' lines: the left one runs through the hull's corner at cell
// (13, 3) and through vertices all the way, the right one crosses a slanted hull edge between
// two of them, and a diagonal corner crosses it off the grid.
TEST(ConstraintAreas, ClipAndEraseAlongTheGridThroughAHullCorner_CutExactlyTheOverlapWithTheHull) {
    TemporaryDirectory directory;
    const fs::path dem = directory.path() / "slanted.tif";
    writeSlantedDem(dem);
    const auto cell = [](double column, double s) {
        return Point2{500005.0 + 10.0 * column, 5000005.0 + 10.0 * s};
    };
    expectClipAndEraseCutTheOverlap(
        dem, {cell(13, -2), cell(19, -2), cell(19, 5), cell(16, 8), cell(13, 5)});
    expectClipAndEraseCutTheOverlap(dem, {cell(4, -3), cell(12, 5), cell(4, 9)});
}

// Near the origin the cut point of a side through the hull's corner rounds to a few ulps
// beyond it, inside the hull, onto the column's edge: the rest of the side runs along that edge
// to the corner and leaves there.
TEST(ConstraintAreas, ClipAndEraseThroughAHullCornerNearTheOrigin_CutExactlyTheOverlapWithTheHull) {
    TemporaryDirectory directory;
    const fs::path dem = directory.path() / "slanted.tif";
    writeSlantedDem(dem, 0.0, 360.0);
    expectClipAndEraseCutTheOverlap(dem,
                                    {{135.0, -21.9}, {195.5, -21.9}, {195.5, 56.8}, {135.0, 56.8}});
    expectClipAndEraseCutTheOverlap(dem,
                                    {{135.0, 21.7}, {195.5, 21.7}, {195.5, 59.8}, {135.0, 59.8}});
}

// The same on a real DEM's jagged nodata border: its bottom hull edge runs from cell centre
// (323851.07, 5101976.98) to (326011.07, 5101916.98).
TEST(ConstraintAreas, ClipAndEraseAcrossARealDemsJaggedBorder_CutExactlyTheOverlapWithTheHull) {
    const fs::path dem = fs::path(TERRATIN_SHARED_DEMS) / "gdalraster__storml_elev_orig.tif";
    if (!fs::exists(dem))
        GTEST_SKIP() << dem << " is absent";
    const std::vector<Point2> ring{
        {324500.5, 5101700.5}, {325500.5, 5101700.5}, {325500.5, 5102500.5}, {324500.5, 5102500.5}};
    expectClipAndEraseCutTheOverlap(dem, ring);
}

TEST(ConstraintAreas, ABowTieOrALineIsRefused) {
    TemporaryDirectory directory;
    const fs::path bowTie = directory.path() / "bowtie.gpkg";
    writeLines(bowTie, {"POLYGON ((455600 5103000, 457000 5104000, 457000 5103000, "
                        "455600 5104000, 455600 5103000))"});
    const fs::path line = directory.path() / "line.gpkg";
    writeLines(line, {"LINESTRING (455300.7 5102700.1, 456000.3 5102900.9)"});
    BuildOptions options;
    options.inputs = {kSample.string()};
    options.output = directory.path() / "tin.ply";
    options.clip = bowTie.string();
    EXPECT_THROW((void)runBuild(options), InvalidInputError);
    options.clip = line.string();
    EXPECT_THROW((void)runBuild(options), InvalidInputError);
    options.clip.clear();
    options.erase = bowTie.string();
    options.refine.emplace();
    options.refine->maxError = 1.0;
    EXPECT_THROW((void)runBuild(options), InvalidInputError); // simplified too
    EXPECT_FALSE(fs::exists(options.output));
}

TEST(BreaklinesPipeline, CrossingLinesMeetAtANewVertex_AndLinesOutsideAreClipped) {
    TemporaryDirectory directory;
    const fs::path lines = directory.path() / "lines.gpkg";
    writeLines(lines, {"LINESTRING (455300.7 5102900.1, 458000.3 5104900.9)",
                       "LINESTRING (455501.3 5104803.7, 457900.9 5102700.2)",
                       "LINESTRING (454000.5 5103000.5, 459000.5 5103700.25)",
                       "LINESTRING (450000 5000000, 451000 5000001)"});
    std::vector<std::string> notices;
    BuildOptions options = optionsFor(lines, directory.path() / "tin.ply");
    options.notice = [&](std::string_view text) { notices.emplace_back(text); };
    const BuildReport report = runBuild(options);
    EXPECT_TRUE(report.validated);
    EXPECT_EQ(report.constraintCrossings, 3U); // each pair of the three inside lines
    EXPECT_EQ(report.clippedBreaklines, 2U);   // the long line cut, the far one dropped
    EXPECT_EQ(report.breaklines, 3U);
    ASSERT_EQ(notices.size(), 1U);
    EXPECT_NE(notices[0].find("2 of the 4 lines"), std::string::npos) << notices[0];
}

TEST(BreaklinesPipeline, LineZRefusesALineWithoutZ) {
    TemporaryDirectory directory;
    const fs::path lines = directory.path() / "lines.gpkg";
    writeLines(lines, {"LINESTRING (455300.7 5102700.1, 456000.3 5102900.9)"});
    BuildOptions options = optionsFor(lines, directory.path() / "tin.ply");
    options.breaklineZ = BreaklineZ::Line;
    EXPECT_THROW((void)runBuild(options), InvalidInputError);
    EXPECT_FALSE(fs::exists(directory.path() / "tin.ply"));
    options.refine.emplace();
    options.refine->maxError = 1.0;
    EXPECT_THROW((void)runBuild(options), InvalidInputError); // simplified too
    EXPECT_FALSE(fs::exists(directory.path() / "tin.ply"));
}

TEST(BreaklinesPipeline, ABadLayerIsRefusedBeforeTheTinIsBuilt) {
    TemporaryDirectory directory;
    const fs::path lines = directory.path() / "lines.gpkg";
    writeLines(lines, {"LINESTRING (455300.7 5102700.1, 456000.3 5102900.9)"});
    for (const bool simplified : {false, true}) {
        BuildOptions options = optionsFor(lines, directory.path() / "tin.ply");
        options.breaklineZ = BreaklineZ::Line; // and the line has no z
        if (simplified) {
            options.refine.emplace();
            options.refine->maxError = 1.0;
        }
        std::vector<std::string> messages;
        const ProgressCallback progress = [&](double, std::string_view message) {
            messages.emplace_back(message);
            return true;
        };
        EXPECT_THROW((void)runBuild(options, progress), InvalidInputError);
        EXPECT_FALSE(messages.empty()); // the DEM was read
        for (const std::string& message : messages) {
            EXPECT_EQ(message.find("triangulat"), std::string::npos) << message;
            EXPECT_EQ(message.find("refin"), std::string::npos) << message;
        }
        EXPECT_FALSE(fs::exists(directory.path() / "tin.ply"));
    }
}

// The layers are read on a thread of their own while the DEM is: a bad DEM is still the error
// reported first, and a missing layer still gets its own error, at full resolution and
// simplified.
TEST(BreaklinesPipeline, LayersReadBesideTheDem_TheDemsErrorComesFirst_AndALayersOwnAfter) {
    TemporaryDirectory directory;
    const fs::path missingLayer = directory.path() / "no_such_lines.gpkg";
    const fs::path missingDem = directory.path() / "no_such_dem.tif";
    for (const bool simplified : {false, true}) {
        BuildOptions options = optionsFor(missingLayer, directory.path() / "tin.ply");
        if (simplified) {
            options.refine.emplace();
            options.refine->maxError = 1.0;
        }
        const auto errorOf = [&] {
            try {
                (void)runBuild(options);
            } catch (const Error& error) {
                return std::string(error.what());
            }
            return std::string("no error");
        };
        const std::string layerError = errorOf();
        EXPECT_NE(layerError.find("no_such_lines.gpkg"), std::string::npos) << layerError;
        options.inputs = {missingDem.string()};
        const std::string demError = errorOf();
        EXPECT_NE(demError.find("no_such_dem.tif"), std::string::npos) << demError;
        EXPECT_EQ(demError.find("no_such_lines.gpkg"), std::string::npos) << demError;
        EXPECT_FALSE(fs::exists(directory.path() / "tin.ply"));
    }
}

TEST(BreaklinesPipeline, AnEmptyLayerGivesANotice_AndALayerInAnotherCrsIsReprojected) {
    TemporaryDirectory directory;
    const fs::path empty = directory.path() / "empty.gpkg";
    writeLines(empty, {});
    // The first segment of the first test, in WGS 84 (EPSG:4326 axis order is handled by OGR).
    const fs::path geographic = directory.path() / "geographic.gpkg";
    OGRSpatialReference utm;
    utm.importFromEPSG(32633);
    OGRSpatialReference wgs84;
    wgs84.importFromEPSG(4326);
    wgs84.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
    utm.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
    std::unique_ptr<OGRCoordinateTransformation> toWgs84(
        OGRCreateCoordinateTransformation(&utm, &wgs84));
    double x[2] = {455501.3, 456700.9};
    double y[2] = {5104003.7, 5103100.2};
    ASSERT_TRUE(toWgs84->Transform(2, x, y));
    char wkt[256];
    std::snprintf(wkt, sizeof wkt, "LINESTRING (%.15g %.15g, %.15g %.15g)", x[0], y[0], x[1], y[1]);
    writeLines(geographic, {wkt}, 4326);

    std::vector<std::string> notices;
    BuildOptions options = optionsFor(empty, directory.path() / "tin.ply");
    options.breaklines.push_back(geographic.string());
    options.notice = [&](std::string_view text) { notices.emplace_back(text); };
    const BuildReport report = runBuild(options);
    EXPECT_TRUE(report.validated);
    EXPECT_EQ(report.breaklines, 1U);
    ASSERT_GE(notices.size(), 1U);
    EXPECT_NE(notices[0].find("has no lines"), std::string::npos) << notices[0];
    // The reprojected ends are within a millimetre of the UTM ones, and joined by an edge.
    const ReadTin tin = readTin(directory.path() / "tin.ply");
    std::vector<Point2> added;
    for (const auto& [place, v] : tin.vertexAt)
        if (std::fmod(place.first - 5.0, 10.0) != 0.0 || std::fmod(place.second - 5.0, 10.0) != 0.0)
            added.push_back({place.first, place.second});
    ASSERT_EQ(added.size(), 2U);
    EXPECT_NEAR(added[0].x, 455501.3, 1e-3);
    EXPECT_TRUE(hasEdge(tin, added[0], added[1]));
}

/// A 40 x 30 GeoTIFF (10 m cells, EPSG:32633) holding saddle(col, row) = 100 + col + 2 row +
/// col row / 4, bilinear in the cell numbers and exact in float32; cell (row 20, col 30) has no
/// data.
double saddle(double col, double row) {
    return 100.0 + col + 2.0 * row + col * row / 4.0;
}
constexpr double kSaddleX0 = 500000.0;
constexpr double kSaddleY0 = 4000000.0;
Point2 saddlePlace(double col, double row) {
    return {kSaddleX0 + (col + 0.5) * 10.0, kSaddleY0 - (row + 0.5) * 10.0};
}

void writeSaddleDem(const fs::path& path) {
    constexpr int kWidth = 40;
    constexpr int kHeight = 30;
    std::vector<float> z(static_cast<std::size_t>(kWidth * kHeight));
    for (int row = 0; row < kHeight; ++row)
        for (int col = 0; col < kWidth; ++col)
            z[static_cast<std::size_t>(row * kWidth + col)] = static_cast<float>(saddle(col, row));
    z[20 * kWidth + 30] = std::numeric_limits<float>::quiet_NaN();
    test::writeElevations(path, kWidth, kHeight, kSaddleX0, kSaddleY0, 10.0, std::move(z));
}

// Regression (the wording): a 2D breakline's vertices took the TIN's z, linear in its
// triangle; on a DEM they take the DEM's, bilinear in the four cells around them, at full
// resolution and simplified alike. Next to a cell without data, the TIN's surface still fills in.
TEST(BreaklinesPipeline, BreaklineVerticesTakeTheDemBilinearly_AtFullResolutionAndSimplified) {
    TemporaryDirectory directory;
    const fs::path dem = directory.path() / "saddle.tif";
    writeSaddleDem(dem);
    const std::vector<std::pair<double, double>> cells{{10.3, 7.6}, {20.7, 12.2}, {33.1, 25.45}};
    std::vector<Point2> places;
    for (const auto& [col, row] : cells)
        places.push_back(saddlePlace(col, row));
    const Point2 byTheHole = saddlePlace(29.6, 19.3); // cell (20, 30) is one of its four
    places.push_back(byTheHole);
    const fs::path lines = directory.path() / "lines.gpkg";
    writeLines(lines, {test::lineWkt(places)});

    for (const bool simplified : {false, true}) {
        BuildOptions options = optionsFor(lines, directory.path() / "tin.ply");
        options.inputs = {dem.string()};
        options.overwrite = true;
        if (simplified) {
            options.refine.emplace();
            options.refine->maxError = 2.0;
        }
        const BuildReport report = runBuild(options);
        EXPECT_TRUE(report.validated);
        const ReadTin tin = readTin(directory.path() / "tin.ply");
        for (std::size_t i = 0; i < cells.size(); ++i)
            EXPECT_NEAR(tin.mesh.vertices[tin.vertexAt.at({places[i].x, places[i].y})].z,
                        saddle(cells[i].first, cells[i].second), 1e-6)
                << "point " << i << (simplified ? ", simplified" : "");
        const double nearHole = tin.mesh.vertices[tin.vertexAt.at({byTheHole.x, byTheHole.y})].z;
        EXPECT_TRUE(std::isfinite(nearHole));
        EXPECT_GT(nearHole, saddle(29.0, 19.0));
        EXPECT_LT(nearHole, saddle(30.0, 20.0));
    }
}

} // namespace
} // namespace terratin

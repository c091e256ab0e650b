// runBuild with --max-error and constraints on the bundled sample DEM, checked from the
// written PLY against the DEM cell by cell: the bound holds over every valid cell of the output's
// area (not inside the lake), the roads' points are vertices, the lake is flat, the clip area is
// exact, and the TIN does not depend on the thread count.

#include "terratin/pipeline/build_pipeline.hpp"

#include "constraint_test_data.hpp"
#include "mesh_readers.hpp"
#include "terratin/crs/grid_projection.hpp"
#include "terratin/crs/reprojection.hpp"
#include "terratin/crs/utm_zone.hpp"
#include "terratin/gdal_error.hpp"
#include "terratin/geometry/predicates.hpp"
#include "terratin/io/height_grid_reader.hpp"

#include <gdal_priv.h>
#include <ogrsf_frmts.h>

#include "temporary_directory.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <memory>
#include <string>
#include <vector>

namespace terratin {
namespace {

namespace fs = std::filesystem;
using test::insideRing;
using test::kSampleColumns;
using test::kSampleRows;
using test::sampleCellCentre;
using test::TemporaryDirectory;

const fs::path kSample = fs::path(TERRATIN_SAMPLE_DEMS) / "ridges_utm.tif";
const std::vector<Point2> kLake = test::sampleLake();
const std::vector<Point2> kRoadA = {
    {455501.3, 5104003.7}, {456700.9, 5102700.2}, {457800.1, 5104500.3}};
const std::vector<Point2> kRoadB = {{455300.7, 5102900.1}, {458000.3, 5104400.9}};

/// Whether `p` lies exactly on a side of the closed `ring`.
bool onRing(const std::vector<Point2>& ring, Point2 p) {
    for (std::size_t i = 0, j = ring.size() - 1; i < ring.size(); j = i++) {
        const Point2 a = ring[j];
        const Point2 b = ring[i];
        if (p.x >= std::min(a.x, b.x) && p.x <= std::max(a.x, b.x) && p.y >= std::min(a.y, b.y) &&
            p.y <= std::max(a.y, b.y) && predicates::orient2d(a, b, p) == 0.0)
            return true;
    }
    return false;
}

/// The TIN in `ply` against the sample, every triangle against every cell centre it holds
/// (closed, exact): the largest error of a valid cell outside the closed `skip` ring (a replace
/// area's shore is flattened with it), and the valid cells in no triangle.
struct Coverage {
    double maxError = 0.0;
    std::size_t uncovered = 0;
};

Coverage coverage(const fs::path& ply, const std::vector<Point2>& skip) {
    const test::ReadMesh mesh = test::readPly(ply);
    const std::vector<float> z = test::readElevations(kSample);
    std::vector<std::uint8_t> covered(z.size(), 0);
    Coverage result;
    for (std::size_t t = 0; t < mesh.triangles.size(); t += 3) {
        const Point3& a = mesh.vertices[mesh.triangles[t]];
        const Point3& b = mesh.vertices[mesh.triangles[t + 1]];
        const Point3& c = mesh.vertices[mesh.triangles[t + 2]];
        const int firstColumn =
            std::max(0, int(std::floor((std::min({a.x, b.x, c.x}) - 455005.0) / 10.0)));
        const int lastColumn = std::min(
            kSampleColumns - 1, int(std::ceil((std::max({a.x, b.x, c.x}) - 455005.0) / 10.0)));
        const int firstRow =
            std::max(0, int(std::floor((5104995.0 - std::max({a.y, b.y, c.y})) / 10.0)));
        const int lastRow = std::min(
            kSampleRows - 1, int(std::ceil((5104995.0 - std::min({a.y, b.y, c.y})) / 10.0)));
        const double area = predicates::orient2d({a.x, a.y}, {b.x, b.y}, {c.x, c.y});
        for (int row = firstRow; row <= lastRow; ++row)
            for (int column = firstColumn; column <= lastColumn; ++column) {
                const Point2 p = sampleCellCentre(column, row);
                const double wa = predicates::orient2d({b.x, b.y}, {c.x, c.y}, p);
                const double wb = predicates::orient2d({c.x, c.y}, {a.x, a.y}, p);
                const double wc = predicates::orient2d({a.x, a.y}, {b.x, b.y}, p);
                const std::size_t cell = static_cast<std::size_t>(row) * kSampleColumns + column;
                if (wa < 0.0 || wb < 0.0 || wc < 0.0 || std::isnan(z[cell]))
                    continue;
                covered[cell] = 1;
                if (!skip.empty() && (insideRing(skip, p) || onRing(skip, p)))
                    continue;
                const double plane = (wa * a.z + wb * b.z + wc * c.z) / area;
                result.maxError = std::max(result.maxError, std::abs(plane - z[cell]));
            }
    }
    for (std::size_t cell = 0; cell < z.size(); ++cell)
        result.uncovered += !std::isnan(z[cell]) && covered[cell] == 0 ? 1 : 0;
    return result;
}

bool hasVertexAt(const test::ReadMesh& mesh, Point2 p) {
    return std::any_of(mesh.vertices.begin(), mesh.vertices.end(),
                       [&](const Point3& v) { return v.x == p.x && v.y == p.y; });
}

BuildOptions roadsAndLake(const TemporaryDirectory& directory, double maxError) {
    test::writeVectorLayer(directory.path() / "roads.gpkg", "roads",
                           {test::lineWkt(kRoadA), test::lineWkt(kRoadB)});
    test::writeVectorLayer(directory.path() / "lake.gpkg", "lake", {test::polygonWkt(kLake)}, 32633,
                           {812.25}, OFTReal);
    BuildOptions options;
    options.inputs = {kSample.string()};
    options.output = directory.path() / "tin.ply";
    options.breaklines = {(directory.path() / "roads.gpkg").string()};
    options.replace = (directory.path() / "lake.gpkg").string();
    options.replaceZField = "level";
    options.refine.emplace();
    options.refine->maxError = maxError;
    options.validate = true;
    return options;
}

/// `dem` refined to `maxError` with the breaklines of `lines`, validated.
BuildOptions simplifiedWithLines(const fs::path& dem, const fs::path& lines, double maxError) {
    BuildOptions options;
    options.inputs = {dem.string()};
    options.breaklines = {lines.string()};
    options.refine.emplace();
    options.refine->maxError = maxError;
    options.validate = true;
    return options;
}

/// Builds `options` on 1 thread and on 2 (tin1.ply, tin2.ply in `directory`; options.output
/// ends as the second), expects the same bytes from both, and returns the two reports.
std::vector<BuildReport> buildOnOneAndTwoThreads(BuildOptions& options, const fs::path& directory) {
    std::vector<BuildReport> reports;
    std::vector<std::string> files;
    for (const unsigned threads : {1U, 2U}) {
        options.triangulation.threads = threads;
        options.output = directory / ("tin" + std::to_string(threads) + ".ply");
        reports.push_back(runBuild(options));
        std::ifstream in(options.output, std::ios::binary);
        files.emplace_back(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    }
    EXPECT_EQ(files[0], files[1]);
    return reports;
}

TEST(SimplifiedConstraints, RoadsAndALake_BoundHoldsOutsideTheLake_LakeFlat_RoadsInTheTin) {
    TemporaryDirectory directory;
    const BuildOptions options = roadsAndLake(directory, 2.0);
    const BuildReport report = runBuild(options);
    EXPECT_TRUE(report.validated); // constrained Delaunay, every road a chain of edges
    EXPECT_EQ(report.breaklines, 2U);
    EXPECT_GT(report.constraintCrossings, 0U);
    EXPECT_LE(report.achievedMaxError, 2.0);
    EXPECT_LT(report.vertices, std::size_t{kSampleColumns} * kSampleRows / 10); // simplified indeed

    const Coverage check = coverage(options.output, kLake);
    EXPECT_LE(check.maxError, 2.0 + 1e-9);
    EXPECT_EQ(check.uncovered, report.uncoveredCells);

    const test::ReadMesh mesh = test::readPly(options.output);
    for (const std::vector<Point2>* road : {&kRoadA, &kRoadB})
        for (const Point2& p : *road)
            EXPECT_TRUE(hasVertexAt(mesh, p)) << p.x << " " << p.y;
    for (std::size_t t = 0; t < mesh.triangles.size(); t += 3) {
        Point2 centroid{0.0, 0.0};
        for (std::size_t i = 0; i < 3; ++i) {
            centroid.x += mesh.vertices[mesh.triangles[t + i]].x / 3.0;
            centroid.y += mesh.vertices[mesh.triangles[t + i]].y / 3.0;
        }
        if (!insideRing(kLake, centroid))
            continue;
        for (std::size_t i = 0; i < 3; ++i)
            EXPECT_EQ(mesh.vertices[mesh.triangles[t + i]].z, 812.25);
    }
}

TEST(SimplifiedConstraints, ALakeWhoseShoreRunsThroughCellCentres_BoundHoldsOnEveryCellOutside) {
    // A diamond on a slope whose sides run through cell centres: those cells lie on the shore,
    // at the lake's level with it, and are not measured; every other valid cell is within the
    // bound, and the report says so.
    TemporaryDirectory directory;
    const std::vector<Point2> diamond = {sampleCellCentre(100, 60), sampleCellCentre(130, 90),
                                         sampleCellCentre(100, 120), sampleCellCentre(70, 90)};
    test::writeVectorLayer(directory.path() / "lake.gpkg", "lake", {test::polygonWkt(diamond)});
    BuildOptions options;
    options.inputs = {kSample.string()};
    options.output = directory.path() / "tin.ply";
    options.replace = (directory.path() / "lake.gpkg").string();
    options.refine.emplace();
    options.refine->maxError = 1.0;
    const BuildReport report = runBuild(options);
    EXPECT_LE(report.achievedMaxError, 1.0);
    const Coverage check = coverage(options.output, diamond);
    EXPECT_LE(check.maxError, 1.0 + 1e-9);
    EXPECT_EQ(check.uncovered, report.uncoveredCells);
}

TEST(SimplifiedConstraints, OneThreadAndTwoGiveTheSameTin) {
    TemporaryDirectory directory;
    BuildOptions options = roadsAndLake(directory, 3.0);
    (void)buildOnOneAndTwoThreads(options, directory.path());
}

TEST(SimplifiedConstraints, ClipKeepsExactlyThePolygon_AndTheBoundHoldsInside) {
    TemporaryDirectory directory;
    test::writeVectorLayer(directory.path() / "area.gpkg", "area", {test::polygonWkt(kLake)});
    BuildOptions options;
    options.inputs = {kSample.string()};
    options.output = directory.path() / "clipped.ply";
    options.clip = (directory.path() / "area.gpkg").string();
    options.refine.emplace();
    options.refine->maxError = 1.5;
    options.validate = true;
    const BuildReport report = runBuild(options);
    EXPECT_GT(report.areaTriangles, 0U);
    const test::ReadMesh mesh = test::readPly(options.output);
    double twiceArea = 0.0;
    for (std::size_t t = 0; t < mesh.triangles.size(); t += 3) {
        const Point3& a = mesh.vertices[mesh.triangles[t]];
        const Point3& b = mesh.vertices[mesh.triangles[t + 1]];
        const Point3& c = mesh.vertices[mesh.triangles[t + 2]];
        twiceArea += (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
    }
    double twiceLake = 0.0;
    for (std::size_t i = 0; i < kLake.size(); ++i)
        twiceLake += kLake[i].x * kLake[(i + 1) % kLake.size()].y -
                     kLake[(i + 1) % kLake.size()].x * kLake[i].y;
    EXPECT_NEAR(twiceArea, twiceLake, 1e-6 * twiceLake);
    EXPECT_LE(coverage(options.output, {}).maxError, 1.5 + 1e-9);
}

TEST(SimplifiedConstraints, ThePointLimitHoldsForTheDemsPoints) {
    TemporaryDirectory directory;
    BuildOptions options = roadsAndLake(directory, 0.5);
    options.refine->maxPoints = 1500;
    const BuildReport report = runBuild(options);
    EXPECT_EQ(report.refineStop, "points");
    EXPECT_LE(report.vertices, 1500U + report.constraintVertices);
}

/// A 160 x 120 GeoTIFF (10 m cells, EPSG:32633) of rolling hills with three open holes: a disc,
/// a long bar and a diagonal band, holes[cell] = 1 in them.
constexpr int kHoledWidth = 160;
constexpr int kHoledHeight = 120;
constexpr double kHoledX0 = 600000.0;
constexpr double kHoledY0 = 5000000.0;

/// Where (column, row) lies, in cell numbers (a cell's centre at whole numbers).
Point2 holedCellCentre(double column, double row) {
    return {kHoledX0 + (column + 0.5) * 10.0, kHoledY0 - (row + 0.5) * 10.0};
}

bool inHoledDemsHole(int column, int row) {
    const bool disc = (column - 45) * (column - 45) + (row - 40) * (row - 40) <= 64;
    const bool bar = row >= 80 && row <= 84 && column >= 60 && column <= 130;
    const bool band = std::abs(column - row - 60) <= 1 && row >= 10 && row <= 50;
    return disc || bar || band;
}

void writeHoledDem(const fs::path& path) {
    std::vector<float> z(std::size_t{kHoledWidth} * kHoledHeight);
    for (int row = 0; row < kHoledHeight; ++row)
        for (int column = 0; column < kHoledWidth; ++column)
            z[std::size_t(row) * kHoledWidth + column] =
                inHoledDemsHole(column, row)
                    ? std::numeric_limits<float>::quiet_NaN()
                    : static_cast<float>(300.0 +
                                         40.0 * std::sin(column / 9.0) * std::cos(row / 7.0) +
                                         0.5 * column);
    test::writeElevations(path, kHoledWidth, kHoledHeight, kHoledX0, kHoledY0, 10.0, std::move(z));
}

// The completion's rounds split the triangles over the holes and reuse their numbers: a mark
// "over a hole" left from an earlier round would drop a triangle that no longer is (or insert
// its cells for nothing). Roads run along, across and around the holes; in the output no
// triangle holds a hole's cell (closed, exact), every valid cell is in one within the bound,
// on one thread and on two.
TEST(SimplifiedConstraints,
     OpenHolesStayUncovered_AndEveryValidCellCovered_AsRoundsChangeTheirTriangles) {
    TemporaryDirectory directory;
    const fs::path dem = directory.path() / "holed.tif";
    writeHoledDem(dem);
    std::vector<std::string> roads;
    for (int k = 0; k < 12; ++k) {
        std::vector<Point2> road;
        for (int step = 0; step <= 30; ++step) {
            const double column = 3.0 + 5.1 * step + 0.37 * k;
            const double row = 6.0 + 9.3 * k + 6.0 * std::sin(step * 0.7 + k);
            road.push_back(holedCellCentre(column, row));
        }
        roads.push_back(test::lineWkt(road));
    }
    test::writeVectorLayer(directory.path() / "roads.gpkg", "roads", roads);
    BuildOptions options = simplifiedWithLines(dem, directory.path() / "roads.gpkg", 0.5);
    for (const BuildReport& report : buildOnOneAndTwoThreads(options, directory.path())) {
        EXPECT_TRUE(report.validated);
        EXPECT_GT(report.constraintCells, 0U);
        EXPECT_GT(report.constraintPasses, 2U);
        EXPECT_GT(report.holeTriangles, 0U);
        EXPECT_EQ(report.areaTriangles, 0U); // the holes' triangles alone are dropped
    }

    const test::ReadMesh mesh = test::readPly(options.output);
    const std::vector<float> z = test::readElevations(dem);
    std::vector<std::uint8_t> covered(z.size(), 0);
    std::size_t holeCellsCovered = 0;
    double maxError = 0.0;
    for (std::size_t t = 0; t < mesh.triangles.size(); t += 3) {
        const Point3& a = mesh.vertices[mesh.triangles[t]];
        const Point3& b = mesh.vertices[mesh.triangles[t + 1]];
        const Point3& c = mesh.vertices[mesh.triangles[t + 2]];
        const double area = predicates::orient2d({a.x, a.y}, {b.x, b.y}, {c.x, c.y});
        for (int row = 0; row < kHoledHeight; ++row)
            for (int column = 0; column < kHoledWidth; ++column) {
                const Point2 p = holedCellCentre(column, row);
                const double wa = predicates::orient2d({b.x, b.y}, {c.x, c.y}, p);
                const double wb = predicates::orient2d({c.x, c.y}, {a.x, a.y}, p);
                const double wc = predicates::orient2d({a.x, a.y}, {b.x, b.y}, p);
                if (wa < 0.0 || wb < 0.0 || wc < 0.0)
                    continue;
                if (inHoledDemsHole(column, row)) {
                    ++holeCellsCovered;
                    continue;
                }
                const std::size_t cell = std::size_t(row) * kHoledWidth + column;
                covered[cell] = 1;
                const double plane = (wa * a.z + wb * b.z + wc * c.z) / area;
                maxError = std::max(maxError, std::abs(plane - z[cell]));
            }
    }
    std::size_t validUncovered = 0;
    for (int row = 0; row < kHoledHeight; ++row)
        for (int column = 0; column < kHoledWidth; ++column)
            validUncovered += !inHoledDemsHole(column, row) &&
                                      covered[std::size_t(row) * kHoledWidth + column] == 0
                                  ? 1
                                  : 0;
    EXPECT_EQ(holeCellsCovered, 0U);
    EXPECT_EQ(validUncovered, 0U);
    EXPECT_LE(maxError, 0.5 + 1e-6);
}

// A geographic DEM (Luxembourg, WGS 84, 46 % nodata outside the border) is refined in its UTM
// zone at its cells' projected positions: a road and an erase area in WGS 84 go into that TIN,
// and the bound holds at every valid cell's projected position outside the erase area.
TEST(SimplifiedConstraints, AGeographicDemWithHoles_RoadAndEraseArea_BoundAtTheProjectedCells) {
    const fs::path dem = fs::path(TERRATIN_SHARED_DEMS) / "terra__elev.tif";
    if (!fs::exists(dem))
        GTEST_SKIP() << "shared DEM not present: " << dem;
    TemporaryDirectory directory;
    const std::vector<Point2> erase = {{6.0, 49.7}, {6.1, 49.7}, {6.1, 49.75}, {6.0, 49.75}};
    test::writeVectorLayer(directory.path() / "road.gpkg", "road",
                           {"LINESTRING (5.9 49.6, 6.1 49.8, 6.3 49.9)"}, 4326);
    test::writeVectorLayer(directory.path() / "erase.gpkg", "erase", {test::polygonWkt(erase)},
                           4326);
    BuildOptions options = simplifiedWithLines(dem, directory.path() / "road.gpkg", 20.0);
    options.erase = (directory.path() / "erase.gpkg").string();
    for (const BuildReport& report : buildOnOneAndTwoThreads(options, directory.path())) {
        EXPECT_TRUE(report.validated);
        EXPECT_EQ(report.breaklines, 1U);
        EXPECT_GT(report.areaTriangles, 0U);
    }

    const io::HeightGridRaster raster = io::readHeightGrid(dem.string(), {});
    const Point2 centre = raster.grid.extentCentre();
    const std::string utm =
        crs::utmZoneCrs(crs::standardUtmZone(centre.x, centre.y), raster.crsWkt);
    const std::vector<Point2> positions = crs::projectCellCentres(raster.grid, raster.crsWkt, utm);
    const crs::Reprojector toUtm(raster.crsWkt, utm);
    std::vector<Point2> eraseUtm;
    for (const Point2& corner : erase)
        eraseUtm.push_back(toUtm.transform(corner));
    const test::ReadMesh mesh = test::readPly(options.output);
    double maxError = 0.0;
    std::size_t measured = 0;
    for (std::size_t t = 0; t < mesh.triangles.size(); t += 3) {
        const Point3& a = mesh.vertices[mesh.triangles[t]];
        const Point3& b = mesh.vertices[mesh.triangles[t + 1]];
        const Point3& c = mesh.vertices[mesh.triangles[t + 2]];
        const double area = predicates::orient2d({a.x, a.y}, {b.x, b.y}, {c.x, c.y});
        for (std::size_t cell = 0; cell < positions.size(); ++cell) {
            const Point2 p = positions[cell];
            const double wa = predicates::orient2d({b.x, b.y}, {c.x, c.y}, p);
            const double wb = predicates::orient2d({c.x, c.y}, {a.x, a.y}, p);
            const double wc = predicates::orient2d({a.x, a.y}, {b.x, b.y}, p);
            if (wa < 0.0 || wb < 0.0 || wc < 0.0 || !raster.grid.isValid(cell) ||
                insideRing(eraseUtm, p))
                continue;
            ++measured;
            const double plane = (wa * a.z + wb * b.z + wc * c.z) / area;
            maxError = std::max(maxError, std::abs(plane - double{raster.grid.z[cell]}));
        }
    }
    EXPECT_GT(measured, raster.grid.validCount() / 2);
    EXPECT_LE(maxError, 20.0 + 1e-6);
}

} // namespace
} // namespace terratin

// runBuild with --replace (hydro-flattening) on the bundled sample DEM, checked from the
// written PLY: the lake is flat at its level, no input point inside it is kept, its boundary
// is in the TIN, and the TIN is exactly constrained Delaunay (validate).

#include "terratin/pipeline/build_pipeline.hpp"

#include "constraint_test_data.hpp"
#include "mesh_readers.hpp"
#include "terratin/error.hpp"
#include "terratin/gdal_error.hpp"

#include <gdal_priv.h>
#include <ogrsf_frmts.h>

#include "temporary_directory.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace terratin {
namespace {

namespace fs = std::filesystem;
using test::insideRing;
using test::kSampleColumns;
using test::kSampleRows;
using test::polygonWkt;
using test::sampleCellCentre;
using test::TemporaryDirectory;

void writePolygons(const fs::path& path, const std::vector<std::string>& wkts,
                   const std::vector<double>& levels = {}, int levelType = OFTReal) {
    test::writeVectorLayer(path, "water", wkts, 32633, levels, levelType);
}

const fs::path kSample = fs::path(TERRATIN_SAMPLE_DEMS) / "ridges_utm.tif";

const std::vector<Point2> kLake = test::sampleLake();

BuildOptions lakeOptions(const fs::path& water, const fs::path& output) {
    BuildOptions options;
    options.inputs = {kSample.string()};
    options.output = output;
    options.replace = water.string();
    options.validate = true;
    return options;
}

Point2 centroid(const test::ReadMesh& mesh, std::size_t t) {
    Point2 sum{0.0, 0.0};
    for (std::size_t i = 0; i < 3; ++i) {
        sum.x += mesh.vertices[mesh.triangles[t + i]].x / 3.0;
        sum.y += mesh.vertices[mesh.triangles[t + i]].y / 3.0;
    }
    return sum;
}

/// The level every triangle inside `ring` has at all three corners; NaN when they differ, or
/// no triangle is inside.
double flatLevelInside(const test::ReadMesh& mesh, const std::vector<Point2>& ring) {
    std::optional<double> level;
    for (std::size_t t = 0; t < mesh.triangles.size(); t += 3) {
        if (!insideRing(ring, centroid(mesh, t)))
            continue;
        for (std::size_t i = 0; i < 3; ++i) {
            const double z = mesh.vertices[mesh.triangles[t + i]].z;
            if (!level)
                level = z;
            if (z != *level)
                return std::nan("");
        }
    }
    return level.value_or(std::nan(""));
}

/// Twice the planimetric area of the triangles inside `ring` (by centroid; all for no ring).
double twiceAreaInside(const test::ReadMesh& mesh, const std::vector<Point2>& ring) {
    double area = 0.0;
    for (std::size_t t = 0; t < mesh.triangles.size(); t += 3) {
        if (!ring.empty() && !insideRing(ring, centroid(mesh, t)))
            continue;
        const Point3& a = mesh.vertices[mesh.triangles[t]];
        const Point3& b = mesh.vertices[mesh.triangles[t + 1]];
        const Point3& c = mesh.vertices[mesh.triangles[t + 2]];
        area += (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
    }
    return area;
}

double twiceArea(const test::ReadMesh& mesh) {
    return twiceAreaInside(mesh, {});
}

double twiceArea(const std::vector<Point2>& ring) {
    double area = 0.0;
    for (std::size_t i = 0; i < ring.size(); ++i)
        area +=
            ring[i].x * ring[(i + 1) % ring.size()].y - ring[(i + 1) % ring.size()].x * ring[i].y;
    return area;
}

TEST(ReplaceAreas, TheLakeIsFlatAtItsFieldLevel_NoInputPointInside_BoundaryInTheTin) {
    TemporaryDirectory directory;
    const fs::path water = directory.path() / "water.gpkg";
    writePolygons(water, {polygonWkt(kLake)}, {812.25});
    BuildOptions options = lakeOptions(water, directory.path() / "tin.ply");
    options.replaceZField = "level";
    const BuildReport report = runBuild(options);
    EXPECT_TRUE(report.validated);
    EXPECT_EQ(report.replacePolygons, 1U);

    std::size_t cellsInside = 0;
    for (int row = 0; row < kSampleRows; ++row)
        for (int column = 0; column < kSampleColumns; ++column)
            cellsInside += insideRing(kLake, sampleCellCentre(column, row)) ? 1 : 0;
    EXPECT_GT(cellsInside, 1000U);
    EXPECT_EQ(report.replacedPoints, cellsInside);

    const test::ReadMesh tin = test::readPly(options.output);
    EXPECT_EQ(flatLevelInside(tin, kLake), 812.25);
    // The ring is a chain of edges: the triangles inside cover exactly the lake.
    EXPECT_NEAR(twiceAreaInside(tin, kLake), twiceArea(kLake), 1e-6 * twiceArea(kLake));
    for (const Point2& corner : kLake)
        EXPECT_NE(std::find_if(tin.vertices.begin(), tin.vertices.end(),
                               [&](const Point3& v) {
                                   return v.x == corner.x && v.y == corner.y && v.z == 812.25;
                               }),
                  tin.vertices.end());
}

TEST(ReplaceAreas, TheDefaultLevelIsTheLowestSurfaceOnTheBoundary) {
    TemporaryDirectory directory;
    const fs::path water = directory.path() / "water.gpkg";
    writePolygons(water, {polygonWkt(kLake)});
    const BuildOptions options = lakeOptions(water, directory.path() / "tin.ply");
    (void)runBuild(options);
    const double level = flatLevelInside(test::readPly(options.output), kLake);
    ASSERT_FALSE(std::isnan(level));

    // The surface on the boundary interpolates the cells around it: the lowest of it lies
    // between the lowest cell near the boundary and, at every corner, the highest cell near
    // that corner (within 1.5 cells: the corners of the triangle holding a boundary point).
    const std::vector<float> z = test::readElevations(kSample);
    const auto near = [](Point2 a, Point2 b) { return std::hypot(a.x - b.x, a.y - b.y) < 15.0; };
    double lowestNear = std::numeric_limits<double>::infinity();
    for (int row = 0; row < kSampleRows; ++row)
        for (int column = 0; column < kSampleColumns; ++column) {
            const Point2 centre = sampleCellCentre(column, row);
            for (std::size_t i = 0; i < kLake.size(); ++i) {
                const Point2 a = kLake[i];
                const Point2 b = kLake[(i + 1) % kLake.size()];
                const double length = std::hypot(b.x - a.x, b.y - a.y);
                bool close = false;
                for (double s = 0; s <= length && !close; s += 2.5)
                    close = near(centre,
                                 {a.x + (b.x - a.x) * s / length, a.y + (b.y - a.y) * s / length});
                if (close)
                    lowestNear = std::min(lowestNear, double{z[row * kSampleColumns + column]});
            }
        }
    EXPECT_GE(level, lowestNear);
    for (const Point2& corner : kLake) {
        double highest = -std::numeric_limits<double>::infinity();
        for (int row = 0; row < kSampleRows; ++row)
            for (int column = 0; column < kSampleColumns; ++column)
                if (near(sampleCellCentre(column, row), corner))
                    highest = std::max(highest, double{z[row * kSampleColumns + column]});
        EXPECT_LE(level, highest);
    }
}

TEST(ReplaceAreas, ARoadAcrossTheLakeIsFlatInside_AndStaysATinEdgeOutside) {
    TemporaryDirectory directory;
    const fs::path water = directory.path() / "water.gpkg";
    writePolygons(water, {polygonWkt(kLake)}, {805.5});
    const fs::path roads = directory.path() / "roads.gpkg";
    test::writeVectorLayer(
        roads, "roads",
        {"LINESTRING (455500.3 5103500.7, 456700.1 5103700.9, 458000.7 5103600.3)"});
    BuildOptions options = lakeOptions(water, directory.path() / "tin.ply");
    options.replaceZField = "level";
    options.breaklines = {roads.string()};
    const BuildReport report = runBuild(options);
    EXPECT_TRUE(report.validated);
    EXPECT_EQ(report.breaklines, 1U);
    EXPECT_EQ(report.constraintCrossings, 2U); // the road enters and leaves the lake
    const test::ReadMesh tin = test::readPly(options.output);
    EXPECT_EQ(flatLevelInside(tin, kLake), 805.5);
    const auto vertexAt = [&](Point2 p) {
        return std::find_if(tin.vertices.begin(), tin.vertices.end(),
                            [&](const Point3& v) { return v.x == p.x && v.y == p.y; });
    };
    ASSERT_NE(vertexAt({456700.1, 5103700.9}), tin.vertices.end());
    EXPECT_EQ(vertexAt({456700.1, 5103700.9})->z, 805.5); // the road's point in the lake
    ASSERT_NE(vertexAt({455500.3, 5103500.7}), tin.vertices.end());
    EXPECT_NE(vertexAt({455500.3, 5103500.7})->z, 805.5); // outside: the surface's
}

TEST(ReplaceAreas, ALakeOverTheDataEdgeKeepsTheHull_AtItsLevel) {
    TemporaryDirectory directory;
    const std::vector<Point2> edgeLake = {{454900.5, 5103000.25},
                                          {455800.75, 5103100.5},
                                          {455700.25, 5104000.75},
                                          {454900.5, 5104100.25}};
    const fs::path water = directory.path() / "water.gpkg";
    writePolygons(water, {polygonWkt(edgeLake)}, {900.0});
    BuildOptions options = lakeOptions(water, directory.path() / "tin.ply");
    options.replaceZField = "level";
    (void)runBuild(options);
    BuildOptions plain;
    plain.inputs = {kSample.string()};
    plain.output = directory.path() / "plain.ply";
    (void)runBuild(plain);
    const test::ReadMesh tin = test::readPly(options.output);
    EXPECT_EQ(flatLevelInside(tin, edgeLake), 900.0);
    const double whole = twiceArea(test::readPly(plain.output));
    EXPECT_NEAR(twiceArea(tin), whole, 1e-12 * whole); // the TIN still covers the data
}

TEST(ReplaceAreas, APointCloudsLakeIsFlatAtTheLowestLevelOfItsShore) {
    // Scattered points of the plane z = x / 100 + y / 50 (text, no CRS): on the lake's shore
    // the surface is lowest at its corner (300, 300), z = 9.
    TemporaryDirectory directory;
    const fs::path points = directory.path() / "points.xyz";
    const std::vector<Point2> lake = {{300.0, 300.0}, {700.0, 350.0}, {500.0, 700.0}};
    std::size_t inLake = 0;
    for (const Point2& p : test::writePlanePoints(points, 3000, 777))
        inLake += insideRing(lake, p) ? 1 : 0;
    const fs::path water = directory.path() / "water.gpkg";
    writePolygons(water, {polygonWkt(lake)});
    BuildOptions options;
    options.inputs = {points.string()};
    options.output = directory.path() / "tin.ply";
    options.replace = water.string();
    options.validate = true;
    const BuildReport report = runBuild(options);
    EXPECT_TRUE(report.validated);
    EXPECT_GT(inLake, 100U);
    EXPECT_EQ(report.replacedPoints, inLake);
    const double level = flatLevelInside(test::readPly(options.output), lake);
    EXPECT_NEAR(level, 9.0, 1e-9);
}

TEST(ReplaceAreas, BadLevelFieldsAreRefusedWithOneLine_AndNoOutputIsLeft) {
    TemporaryDirectory directory;
    const fs::path output = directory.path() / "tin.ply";
    const auto refusal = [&](const BuildOptions& options) {
        try {
            (void)runBuild(options);
        } catch (const InvalidInputError& error) {
            EXPECT_FALSE(fs::exists(output));
            return std::string(error.what());
        }
        return std::string("no error");
    };
    const fs::path unset = directory.path() / "unset.gpkg";
    writePolygons(unset, {polygonWkt(kLake)}, {std::nan("")});
    BuildOptions options = lakeOptions(unset, output);
    options.replaceZField = "level";
    EXPECT_NE(refusal(options).find("feature 1 has no value in field 'level'"), std::string::npos);
    options.replaceZField = "depth";
    EXPECT_NE(refusal(options).find("no field 'depth'; its fields: 'level'"), std::string::npos);

    const fs::path text = directory.path() / "text.gpkg";
    writePolygons(text, {polygonWkt(kLake)}, {}, OFTString);
    options = lakeOptions(text, output);
    options.replaceZField = "level";
    EXPECT_NE(refusal(options).find("field 'level' is not numeric"), std::string::npos);

    const fs::path outside = directory.path() / "outside.gpkg";
    writePolygons(outside, {"POLYGON ((0 0, 10 0, 10 10, 0 0))"});
    options = lakeOptions(outside, output);
    EXPECT_NE(refusal(options).find("boundary lies outside the data"), std::string::npos);

    options = lakeOptions(unset, output);
    options.replace.clear();
    options.replaceZField = "level";
    EXPECT_NE(refusal(options).find("give them too"), std::string::npos);
}

} // namespace
} // namespace terratin

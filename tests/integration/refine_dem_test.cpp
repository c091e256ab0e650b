// Refinement of real DEMs from ../shared/dems (skipped when absent): the grid reader agrees
// with the point reader cell by cell, and the max-error guarantee, the holes and the thread
// invariance hold on real nodata patterns.

#include "refine_test_grids.hpp"

#include "terratin/crs/grid_projection.hpp"
#include "terratin/crs/utm_zone.hpp"
#include "terratin/io/height_grid_reader.hpp"
#include "terratin/io/raster_reader.hpp"
#include "terratin/refine/refine.hpp"
#include "terratin/tile/refine_tiles.hpp"
#include "terratin/triangulate/mesh_validation.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace terratin {
namespace {

namespace fs = std::filesystem;

std::string sharedDem(const std::string& name) {
    return (fs::path(TERRATIN_SHARED_DEMS) / name).string();
}

// Every cell centre of `grid` (in `wkt`, geographic) projected to the UTM zone of the grid's
// centre, as the build pipeline does it.
std::vector<Point2> utmPositions(const HeightGrid& grid, const std::string& wkt) {
    const Point2 centre = grid.extentCentre();
    return crs::projectCellCentres(grid, wkt,
                                   crs::utmZoneCrs(crs::standardUtmZone(centre.x, centre.y), wkt));
}

// The first size x size window (stepping by half a window) with between 2 % and 40 % of its
// cells without data, as a grid of its own.
HeightGrid windowWithNodata(const HeightGrid& grid, int size) {
    for (int top = 0; top + size <= grid.height; top += size / 2)
        for (int left = 0; left + size <= grid.width; left += size / 2) {
            std::size_t nodata = 0;
            for (int row = top; row < top + size; ++row)
                for (int col = left; col < left + size; ++col)
                    nodata +=
                        grid.isValid(static_cast<std::size_t>(row) * grid.width + col) ? 0U : 1U;
            const double share = static_cast<double>(nodata) / (size * size);
            if (share < 0.02 || share > 0.4)
                continue;
            HeightGrid window;
            window.width = size;
            window.height = size;
            const Point2 corner = grid.cellCentre(top, left);
            window.geoTransform = grid.geoTransform;
            window.geoTransform[0] =
                corner.x - 0.5 * grid.geoTransform[1] - 0.5 * grid.geoTransform[2];
            window.geoTransform[3] =
                corner.y - 0.5 * grid.geoTransform[4] - 0.5 * grid.geoTransform[5];
            window.z.resize(window.cellCount());
            for (int row = 0; row < size; ++row)
                for (int col = 0; col < size; ++col)
                    window.z[static_cast<std::size_t>(row) * size + col] =
                        grid.z[static_cast<std::size_t>(row + top) * grid.width + col + left];
            return window;
        }
    return {};
}

#define SKIP_WITHOUT(path)                                                                         \
    if (!fs::exists(path))                                                                         \
    GTEST_SKIP() << "shared DEM not present: " << (path)

TEST(RefineDem, GridReaderMatchesPointReader_CellByCell) {
    for (const char* name :
         {"gdalraster__storml_elev_orig.tif", "terra__elev.tif", "pyterra__dgm5.tif"}) {
        const std::string path = sharedDem(name);
        SKIP_WITHOUT(path);
        const io::HeightGridRaster raster = io::readHeightGrid(path, {});
        const io::RasterPoints points = io::readRasterPoints(path, {});
        ASSERT_EQ(raster.skippedCells, points.skippedCells) << name;
        std::size_t valid = 0;
        for (std::size_t cell = 0; cell < raster.grid.cellCount(); ++cell)
            valid += raster.grid.isValid(cell) ? 1U : 0U;
        ASSERT_EQ(valid, points.points.size());
        for (std::size_t i = 0; i < points.points.size(); ++i) {
            const std::uint64_t cell = points.cellIndex[i];
            const Point2 centre = raster.grid.cellCentre(cell);
            ASSERT_EQ(centre.x, points.points[i].x) << name << " cell " << cell;
            ASSERT_EQ(centre.y, points.points[i].y) << name << " cell " << cell;
            ASSERT_EQ(static_cast<double>(raster.grid.z[cell]), points.points[i].z);
        }
        EXPECT_EQ(raster.crsWkt, points.crsWkt);
    }
}

// A raster read a window at a time holds bit for bit readHeightGrid's cells, and the
// tiles refined from its windows are the tiles refined from the whole grid.
TEST(RefineDem, RasterWindowsHoldTheGridsCells_AndGiveItsTiledTin) {
    const std::string path = std::string(TERRATIN_SAMPLE_DEMS) + "/ridges_utm.tif";
    const io::HeightGridRaster raster = io::readHeightGrid(path, {});
    const HeightGrid& grid = raster.grid;
    io::RasterCells cells(path, {});
    ASSERT_EQ(cells.width(), grid.width);
    ASSERT_EQ(cells.height(), grid.height);
    EXPECT_EQ(cells.geoTransform(), grid.geoTransform);
    EXPECT_EQ(cells.crsWkt(), raster.crsWkt);
    for (const auto& [top, left, rows, columns] : {std::array{0, 0, 1, 1},
                                                   {0, 0, grid.height, grid.width},
                                                   {17, 250, 100, 70},
                                                   {grid.height - 3, grid.width - 5, 3, 5}}) {
        const HeightGrid window = cells.window(top, rows, left, columns);
        ASSERT_EQ(window.firstRow, top);
        ASSERT_EQ(window.firstColumn, left);
        for (int row = 0; row < rows; ++row)
            for (int col = 0; col < columns; ++col) {
                const float z = grid.z[static_cast<std::size_t>(top + row) * grid.width +
                                       static_cast<std::size_t>(left + col)];
                const float got = window.z[static_cast<std::size_t>(row * columns + col)];
                ASSERT_TRUE(std::isnan(z) ? std::isnan(got) : got == z)
                    << "row " << top + row << ", column " << left + col;
                ASSERT_EQ(window.cellCentre(row, col), grid.cellCentre(top + row, left + col));
            }
    }
    EXPECT_THROW(static_cast<void>(cells.window(0, 1, grid.width, 1)), std::out_of_range);

    RefineOptions options = test::validatedOptions(0.5, 1);
    options.maxHole = 3;
    TileOptions tiles;
    tiles.tileSize = 50;
    const RefineResult whole = refineTiles(grid, options, tiles);
    const RefineResult windows = refineTiles(cells, options, tiles);
    EXPECT_EQ(windows.mesh.vertices, whole.mesh.vertices);
    EXPECT_EQ(windows.mesh.triangles, whole.mesh.triangles);
    EXPECT_EQ(windows.mesh.neighbours, whole.mesh.neighbours);
    EXPECT_EQ(windows.openHoleCells, whole.openHoleCells);
    EXPECT_EQ(windows.coveredCells, whole.coveredCells);
    EXPECT_GT(windows.openHoleCells, 0U);
}

TEST(RefineDem, EveryValidCellWithinMaxError_AndHolesWhereTheNodataIs) {
    // terra__elev.tif has 1 km cells of hilly terrain: 2 m would need almost every cell.
    for (const auto& [name, maxError] :
         {std::pair("gdalraster__storml_elev_orig.tif", 2.0), std::pair("terra__elev.tif", 20.0)}) {
        const std::string path = sharedDem(name);
        SKIP_WITHOUT(path);
        const HeightGrid grid = io::readHeightGrid(path, {}).grid;
        RefineOptions options;
        options.maxError = maxError;
        options.threads = 2;
        options.validate = true;
        const RefineResult result = refine(grid, options);
        EXPECT_TRUE(result.validated);
        EXPECT_LE(result.maxError, maxError) << name;
        EXPECT_LT(result.mesh.vertexCount(), grid.validCount() / 2) << name;
        const test::CoverageCheck check = test::checkCoverage(result.mesh, grid, options.maxHole);
        EXPECT_LE(check.maxError, maxError + 1e-6) << name;
        EXPECT_EQ(check.coveredOpenHoleCells, 0U) << name;
        EXPECT_EQ(check.uncoveredValid, result.uncoveredCells) << name;
        test::expectEmptyCircumcircles(result.mesh);
    }
}

TEST(RefineDem, SameVertexCountForOneAndTwoThreads) {
    const std::string path = sharedDem("terra__elev_vinschgau.tif");
    SKIP_WITHOUT(path);
    const HeightGrid grid = io::readHeightGrid(path, {}).grid;
    RefineOptions options;
    options.maxError = 10.0;
    options.threads = 1;
    const RefineResult one = refine(grid, options);
    options.threads = 2;
    const RefineResult two = refine(grid, options);
    EXPECT_EQ(one.mesh.vertexCount(), two.mesh.vertexCount());
    EXPECT_EQ(one.mesh.triangleCount(), two.mesh.triangleCount());
    EXPECT_EQ(one.maxError, two.maxError);
    EXPECT_LE(two.maxError, 10.0);
}

TEST(RefineDem, LimitsRespected_OnARealDem) {
    const std::string path = sharedDem("whiteboxR__DEM.tif");
    SKIP_WITHOUT(path);
    const HeightGrid grid = io::readHeightGrid(path, {}).grid;
    RefineOptions options;
    options.maxError = 0.0;
    options.maxPoints = 2000;
    options.threads = 2;
    const RefineResult points = refine(grid, options);
    EXPECT_EQ(points.stop, RefineStop::PointLimit);
    EXPECT_LE(points.mesh.vertexCount(), 2000U);
    options.maxPoints.reset();
    options.maxTriangles = 3000;
    const RefineResult triangles = refine(grid, options);
    EXPECT_EQ(triangles.stop, RefineStop::TriangleLimit);
    EXPECT_LE(triangles.mesh.triangleCount(), 3000U);
}

TEST(RefineDem, GeographicEverest_RefinedInItsUtmZone_WithHolesOverTheVoids) {
    const std::string path = sharedDem("osgearth__mt_everest_90m.tif");
    SKIP_WITHOUT(path);
    const io::HeightGridRaster raster = io::readHeightGrid(path, {});
    RefineOptions options;
    options.maxError = 5.0;
    options.threads = 2;
    options.validate = true;
    // The whole DEM: the refiner's own exact check over every cell (it throws on failure).
    {
        const std::vector<Point2> positions = utmPositions(raster.grid, raster.crsWkt);
        const RefineResult result = refine(raster.grid, positions, options);
        EXPECT_TRUE(result.validated);
        EXPECT_LE(result.maxError, 5.0);
        EXPECT_GT(result.openHoleCells, 0U);
        EXPECT_GT(result.droppedTriangles, 0U);
        EXPECT_LT(result.mesh.vertexCount(), raster.grid.validCount() * 2 / 3);
    }
    // A window with voids, checked cell by cell against every triangle by brute force.
    const HeightGrid window = windowWithNodata(raster.grid, 90);
    ASSERT_GT(window.cellCount(), 0U);
    const std::vector<Point2> positions = utmPositions(window, raster.crsWkt);
    const RefineResult result = refine(window, positions, options);
    EXPECT_GT(result.droppedTriangles, 0U);
    const test::CoverageCheck check =
        test::checkCoverage(result.mesh, window, options.maxHole, positions);
    EXPECT_LE(check.maxError, 5.0 + 1e-6);
    EXPECT_EQ(check.coveredOpenHoleCells, 0U);
    EXPECT_EQ(check.uncoveredValid, result.uncoveredCells);
    test::expectEmptyCircumcircles(result.mesh);
}

} // namespace
} // namespace terratin

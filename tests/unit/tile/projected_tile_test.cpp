// Tiles at projected positions (projected_tile.hpp, a geographic DEM refined in its UTM zone):
// the joined TIN is one conforming triangulation at the cells' positions, each tile a
// constrained Delaunay TIN (Tiled::validate), every valid cell within the bound or
// reported uncovered (checked by a scan that shares no code with the refiner), and the TIN does
// not depend on the thread count. The maps bend rows into arcs far more than any projection.

#include "../refine/refine_test_grids.hpp"
#include "conforming_tin.hpp"
#include "mesh_invariants.hpp"

#include "tiled_refine_options.hpp"

#include "terratin/refine/refine.hpp"
#include "terratin/tile/refine_tiles.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <set>
#include <string>
#include <vector>

namespace terratin {
namespace {

// The refiner's options and the tiles' together, as each test states them (options.maxError,
// options.tileSize), refined by refineTiles.
using Tiled = detail::TiledRefineOptions;

RefineResult refine(const HeightGrid& grid, const Tiled& options,
                    const ProgressCallback& progress = {}) {
    return refineTiles(grid, options, options, progress);
}

using test::expectConforming;
using test::xy;

/// Rows bent into arcs around a centre 200 cells below the grid, as refine_positions_test's
/// map; `mirrored` flips x, so that the map keeps the pixel frame's orientation instead of
/// turning it over.
Point2 bent(Point2 centre, bool mirrored) {
    constexpr double kRadius = 200.0;
    const double radius = kRadius + centre.y;
    const double x = radius * std::sin(centre.x / kRadius);
    return {1000.0 + (mirrored ? -x : x), 5000.0 + radius * std::cos(centre.x / kRadius)};
}

std::vector<Point2> positionsOf(const HeightGrid& window, bool mirrored) {
    std::vector<Point2> positions(window.cellCount());
    for (std::size_t cell = 0; cell < positions.size(); ++cell)
        positions[cell] = bent(window.cellCentre(std::uint64_t{cell}), mirrored);
    return positions;
}

Tiled tiledAt(double maxError, std::size_t tileSize, bool mirrored, unsigned threads = 1) {
    Tiled options(test::validatedOptions(maxError, threads), {});
    options.tileSize = tileSize;
    options.cellPositions = [mirrored](const HeightGrid& window) {
        return positionsOf(window, mirrored);
    };
    return options;
}

Tiled everyCellAt(std::size_t tileSize, bool mirrored) {
    Tiled options = tiledAt(0.0, tileSize, mirrored);
    options.maxError.reset();
    options.everyCell = true;
    return options;
}

/// EXPECTs each vertex at its own cell's position with its elevation.
void expectVerticesAtTheirCells(const TinMesh& mesh, const HeightGrid& grid,
                                const std::vector<Point2>& positions) {
    std::set<std::uint32_t> cells;
    for (std::size_t v = 0; v < mesh.vertexCount(); ++v) {
        const std::uint32_t cell = mesh.sourceIndex[v];
        EXPECT_TRUE(cells.insert(cell).second) << "cell " << cell << " twice";
        EXPECT_EQ(xy(mesh.vertices[v]), positions[cell]);
        EXPECT_EQ(mesh.vertices[v].z, double{grid.z[cell]});
    }
}

TEST(TilesAtPositions, OneConformingTin_WithinTheBound_EachTileConstrainedDelaunay) {
    const HeightGrid grid = test::roughTerrain(97, 83, 7);
    const double maxError = 2.0;
    for (const bool mirrored : {false, true}) {
        const std::vector<Point2> positions = positionsOf(grid, mirrored);
        const RefineResult untiled = refine(grid, positions, test::validatedOptions(maxError, 2));
        for (const std::size_t tileSize : {16, 40}) {
            SCOPED_TRACE("tile size " + std::to_string(tileSize) + (mirrored ? ", mirrored" : ""));
            const RefineResult result = refine(grid, tiledAt(maxError, tileSize, mirrored));
            EXPECT_TRUE(result.validated);
            const test::EdgeCount edges = expectConforming(result.mesh);
            // A disc: V - E + F = 1.
            EXPECT_EQ(result.mesh.vertexCount() + result.mesh.triangleCount(),
                      1 + edges.interior + edges.boundary);
            const test::CoverageCheck check = test::checkCoverage(result.mesh, grid, 1, positions);
            EXPECT_LE(check.maxError, maxError + 1e-6);
            EXPECT_EQ(check.uncoveredValid, 0U);
            EXPECT_EQ(result.uncoveredCells, 0U);
            EXPECT_EQ(result.coveredCells, grid.cellCount());
            EXPECT_LE(result.maxError, maxError);
            expectVerticesAtTheirCells(result.mesh, grid, positions);
            // About as many points as untiled: the sides cost some.
            EXPECT_LT(result.mesh.vertexCount(), untiled.mesh.vertexCount() * 6 / 5);
        }
    }
}

TEST(TilesAtPositions, TheSameTinForOneThreadAndTwo) {
    const HeightGrid grid = test::roughTerrain(120, 90, 11);
    const RefineResult one = refine(grid, tiledAt(1.5, 32, false, 1));
    const RefineResult two = refine(grid, tiledAt(1.5, 32, false, 2));
    test::expectSameTriangles(one.mesh, two.mesh);
    EXPECT_EQ(one.mesh.vertices, two.mesh.vertices);
    EXPECT_EQ(one.mesh.sourceIndex, two.mesh.sourceIndex);
    EXPECT_EQ(one.maxError, two.maxError);
}

TEST(TilesAtPositions, NoDataAcrossSidesAndCorners_TheUncoveredReportedAreTheCellsNoTileCovers) {
    // A shore of one-cell peninsulas and a sea below: holes across sides, tiles without data,
    // corners without data, refined and at full resolution.
    for (const std::size_t tileSize : {5U, 8U, 20U}) {
        for (std::uint32_t seed = 1; seed <= 3; ++seed) {
            const HeightGrid grid = test::shoreWithPeninsulas(seed);
            const std::vector<Point2> positions = positionsOf(grid, false);
            for (const bool everyCell : {false, true}) {
                SCOPED_TRACE("tile size " + std::to_string(tileSize) + ", seed " +
                             std::to_string(seed) + (everyCell ? ", every cell" : ""));
                const RefineResult result = refine(grid, everyCell ? everyCellAt(tileSize, false)
                                                                   : tiledAt(1.0, tileSize, false));
                expectConforming(result.mesh);
                const test::CoverageCheck check =
                    test::checkCoverage(result.mesh, grid, 1, positions);
                EXPECT_EQ(result.uncoveredCells, check.uncoveredValid);
                EXPECT_EQ(check.uncoveredValid, 0U);
                EXPECT_EQ(check.coveredOpenHoleCells, 0U);
                EXPECT_LE(check.maxError, 1.0 + 1e-6);
                expectVerticesAtTheirCells(result.mesh, grid, positions);
            }
        }
    }
}

TEST(TilesAtPositions, EveryCell_EachValidCellAVertex) {
    const HeightGrid grid = test::makeGrid(45, 38, [](int row, int col) {
        return (row * 7 + col * 3) % 41 == 0 ? std::nan("")
                                             : 50.0 + 4.0 * std::sin(row * 0.3 + col * 0.2);
    });
    std::size_t valid = 0;
    for (std::size_t cell = 0; cell < grid.cellCount(); ++cell)
        valid += grid.isValid(cell) ? 1U : 0U;
    for (const bool mirrored : {false, true}) {
        const RefineResult result = refine(grid, everyCellAt(12, mirrored));
        EXPECT_EQ(result.mesh.vertexCount(), valid);
        expectConforming(result.mesh);
        const std::vector<Point2> positions = positionsOf(grid, mirrored);
        const test::CoverageCheck check = test::checkCoverage(result.mesh, grid, 1, positions);
        EXPECT_EQ(check.uncoveredValid, 0U);
        EXPECT_LT(check.maxError, 1e-9); // the check's own rounding
        expectVerticesAtTheirCells(result.mesh, grid, positions);
    }
}

TEST(TilesAtPositions, APointLimitSharedAmongTheTiles_HoldsForTheWhole) {
    const HeightGrid grid = test::roughTerrain(90, 70, 5);
    Tiled options = tiledAt(0.1, 30, false);
    options.maxPoints = 1500;
    const RefineResult result = refine(grid, options);
    EXPECT_EQ(result.stop, RefineStop::PointLimit);
    EXPECT_LE(result.mesh.vertexCount(), 1500U);
    expectConforming(result.mesh);
}

} // namespace
} // namespace terratin

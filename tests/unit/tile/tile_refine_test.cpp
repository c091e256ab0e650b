// Refinement in tiles: the joined TIN is conforming (no crack, no T-junction, no
// overlap), each tile side carries exactly the vertices chosen from its own cells, every valid
// cell is within the bound (checked by a scan that shares no code with the refiner), and the
// TIN does not depend on the thread count.

#include "border_profile.hpp"
#include "one_tile.hpp"
#include "tile_grid.hpp"
#include "tile_refinement.hpp"

#include "../refine/refine_test_grids.hpp"
#include "conforming_tin.hpp"
#include "mesh_invariants.hpp"

#include "terratin/error.hpp"
#include "terratin/geometry/predicates.hpp"
#include "tiled_refine_options.hpp"

#include "terratin/refine/refine.hpp"
#include "terratin/tile/refine_tiles.hpp"
#include "terratin/tile/tile_distribution.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <functional>
#include <limits>
#include <map>
#include <mutex>
#include <set>
#include <thread>
#include <utility>
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

using test::areaSum;
using test::EdgeCount;
using test::expectConforming;
using test::xy;

constexpr double kNoData = std::numeric_limits<double>::quiet_NaN();

Tiled tiled(double maxError, std::size_t tileSize, unsigned threads = 1) {
    Tiled options(test::validatedOptions(maxError, threads), {});
    options.tileSize = tileSize;
    return options;
}

/// The vertex cells of `mesh` (sourceIndex) in the cells `line` of a grid, as indices into
/// `line`.
std::vector<std::uint32_t> verticesAlong(const TinMesh& mesh,
                                         const std::vector<std::size_t>& line) {
    const std::set<std::uint32_t> cells(mesh.sourceIndex.begin(), mesh.sourceIndex.end());
    std::vector<std::uint32_t> found;
    for (std::size_t k = 0; k < line.size(); ++k)
        if (cells.count(static_cast<std::uint32_t>(line[k])) != 0)
            found.push_back(static_cast<std::uint32_t>(k));
    return found;
}

/// EXPECTs that every tile side of the cut carries exactly the vertices keptBorderCells
/// chooses from that side's cells alone (within the refiner's tolerance for sides), and no
/// other.
void expectSidesFromTheirCells(const TinMesh& mesh, const HeightGrid& grid, std::size_t tileSize,
                               double maxError) {
    const auto width = static_cast<std::size_t>(grid.width);
    const detail::TileGrid tiles(width, static_cast<std::size_t>(grid.height), tileSize);
    for (std::size_t ty = 0; ty < tiles.tileRows(); ++ty)
        for (std::size_t tx = 0; tx < tiles.tileColumns(); ++tx) {
            const detail::CellRange rows = tiles.rowsOf(ty);
            const detail::CellRange columns = tiles.columnsOf(tx);
            std::vector<std::vector<std::size_t>> sides(4);
            for (std::size_t c = columns.first; c <= columns.last; ++c) {
                sides[0].push_back(rows.first * width + c);
                sides[1].push_back(rows.last * width + c);
            }
            for (std::size_t r = rows.first; r <= rows.last; ++r) {
                sides[2].push_back(r * width + columns.first);
                sides[3].push_back(r * width + columns.last);
            }
            for (const std::vector<std::size_t>& side : sides) {
                std::vector<float> z;
                for (const std::size_t cell : side)
                    z.push_back(grid.z[cell]);
                const double tolerance = detail::sideTolerance(z, maxError);
                EXPECT_LT(tolerance, maxError);
                EXPECT_GT(tolerance, maxError - 1e-4);
                EXPECT_EQ(verticesAlong(mesh, side), detail::keptBorderCells(z, tolerance))
                    << "the side from cell " << side.front() << " to " << side.back();
            }
        }
}

TEST(TiledRefine, OneConformingTin_SidesFromTheirCells_WithinTheBound) {
    const HeightGrid grid = test::roughTerrain(97, 83, 7);
    const double maxError = 2.0;
    for (const std::size_t tileSize : {16, 40}) {
        SCOPED_TRACE("tile size " + std::to_string(tileSize));
        const RefineResult result = refine(grid, tiled(maxError, tileSize));
        const TinMesh& mesh = result.mesh;
        const EdgeCount edges = expectConforming(mesh);
        // A disc: V - E + F = 1, its boundary the rectangle of the cell centres.
        EXPECT_EQ(mesh.vertexCount() + mesh.triangleCount(), 1 + edges.interior + edges.boundary);
        EXPECT_DOUBLE_EQ(areaSum(mesh), 96.0 * 82.0);
        expectSidesFromTheirCells(mesh, grid, tileSize, maxError);
        test::expectWithinError(mesh, grid, maxError);
        EXPECT_LE(result.maxError, maxError);
        EXPECT_EQ(result.coveredCells, grid.cellCount());
        EXPECT_EQ(result.uncoveredCells, 0U);
        EXPECT_TRUE(result.validated);
        // Simplified: far fewer vertices than cells, each cell one vertex at its centre.
        EXPECT_LT(mesh.vertexCount(), grid.cellCount() / 3);
        std::set<std::uint32_t> cells;
        for (std::size_t v = 0; v < mesh.vertexCount(); ++v) {
            EXPECT_TRUE(cells.insert(mesh.sourceIndex[v]).second) << "cell " << mesh.sourceIndex[v];
            const Point2 centre = grid.cellCentre(std::uint64_t{mesh.sourceIndex[v]});
            EXPECT_EQ(xy(mesh.vertices[v]), centre);
        }
    }
}

TEST(TiledRefine, TheSameTinForOneThreadAndTwo) {
    const HeightGrid grid = test::roughTerrain(120, 90, 11);
    const RefineResult one = refine(grid, tiled(1.5, 32, 1));
    const RefineResult two = refine(grid, tiled(1.5, 32, 2));
    // The triangles' order follows the threads, as untiled.
    test::expectSameTriangles(one.mesh, two.mesh);
    EXPECT_EQ(one.mesh.vertices, two.mesh.vertices); // tile by tile, each in cell order
    EXPECT_EQ(one.mesh.sourceIndex, two.mesh.sourceIndex);
    EXPECT_EQ(one.maxError, two.maxError);
}

TEST(TiledRefine, NoDataAcrossSides_AnEmptyTile_AndALastTileOneCellWide) {
    // Tiles of 20: columns 0-20, 20-40, 40-41 (the last one cell beyond its side); rows 0-20,
    // 20-40, 40-45. Discs of no data (open holes) across the side at column 20 and the one at
    // row 20, the tile of rows 0-20 and columns 0-20 all no data, its sides too, and single
    // nodata cells (filled).
    const HeightGrid grid = test::makeGrid(42, 46, [](int row, int col) {
        const auto inDisc = [&](double centreRow, double centreColumn) {
            return (row - centreRow) * (row - centreRow) +
                       (col - centreColumn) * (col - centreColumn) <
                   30.0;
        };
        if (inDisc(29.5, 20.0) || inDisc(20.0, 30.5) || (row <= 20 && col <= 20))
            return kNoData;
        if ((row * 7 + col * 3) % 97 == 0)
            return kNoData;
        return 100.0 + 10.0 * std::sin(row * 0.3) * std::cos(col * 0.25) + 0.1 * (row % 3);
    });
    const double maxError = 0.5;
    for (const unsigned threads : {1U, 2U}) {
        SCOPED_TRACE("threads " + std::to_string(threads));
        const RefineResult result = refine(grid, tiled(maxError, 20, threads));
        expectConforming(result.mesh);
        expectSidesFromTheirCells(result.mesh, grid, 20, maxError);
        const test::CoverageCheck check = test::checkCoverage(result.mesh, grid, 1);
        EXPECT_LE(check.maxError, maxError + 1e-6);
        EXPECT_EQ(check.uncoveredValid, 0U);
        EXPECT_EQ(check.coveredOpenHoleCells, 0U);
        EXPECT_GT(result.openHoleCells, 0U);
        EXPECT_EQ(result.uncoveredCells, 0U);
    }
}

TEST(TiledRefine, HolesAcrossSides_DecidedFromTheTilesMarginsAsFromTheWholeGrid) {
    // --max-hole 6 against nodata regions across the sides at row 20 and column 20 (tiles of
    // 20): 6 cells (filled), 7 cells (open), 6 cells in an L about a corner of four tiles
    // (filled), a diagonal line of 12 cells, 8-connected (open).
    const std::set<std::pair<int, int>> nodata = {
        {19, 5},  {20, 5},  {21, 5},  {19, 6},  {20, 6},  {21, 6},            // 6 across row 20
        {8, 19},  {8, 20},  {8, 21},  {9, 19},  {9, 20},  {9, 21},  {10, 20}, // 7 across col 20
        {19, 19}, {20, 19}, {21, 19}, {21, 20}, {21, 21}, {21, 22},           // 6, an L
        {30, 14}, {31, 15}, {32, 16}, {33, 17}, {34, 18}, {35, 19}, {36, 20},
        {37, 21}, {38, 22}, {39, 23}, {40, 24}, {41, 25}}; // 12, diagonal
    const HeightGrid grid = test::makeGrid(45, 45, [&](int row, int col) {
        return nodata.count({row, col}) != 0 ? kNoData
                                             : 20.0 + 3.0 * std::sin(row * 0.4) + 0.05 * col * row;
    });
    Tiled options = tiled(0.2, 20);
    options.maxHole = 6;
    const RefineResult result = refine(grid, options);
    const std::vector<std::uint8_t> open = openHoleCells(grid, options);
    EXPECT_EQ(result.openHoleCells,
              static_cast<std::size_t>(std::count(open.begin(), open.end(), 1)));
    EXPECT_EQ(result.openHoleCells, 7U + 12U);
    expectConforming(result.mesh);
    const test::CoverageCheck check = test::checkCoverage(result.mesh, grid, 6);
    EXPECT_EQ(check.coveredOpenHoleCells, 0U);
    EXPECT_EQ(check.uncoveredValid, 0U);
    EXPECT_LE(check.maxError, 0.2 + 1e-6);
}

TEST(TiledRefine, AValidCellHangingIntoAnOpenHole_IsCovered) {
    // A tile's vertex that only triangles over an open hole use gets its valid neighbours as
    // vertices, as untiled (stranded_cells.hpp), so the valid cell beside the hole is covered.
    for (std::uint32_t seed = 1; seed <= 6; ++seed) {
        SCOPED_TRACE("seed " + std::to_string(seed));
        const HeightGrid grid = test::shoreWithPeninsulas(seed);
        const RefineResult result = refine(grid, tiled(2.0, 20));
        expectConforming(result.mesh);
        const test::CoverageCheck check = test::checkCoverage(result.mesh, grid, 1);
        EXPECT_EQ(check.uncoveredValid, 0U);
        EXPECT_EQ(result.uncoveredCells, 0U);
        EXPECT_EQ(check.coveredOpenHoleCells, 0U);
        EXPECT_LE(check.maxError, 2.0 + 1e-6);
    }
}

TEST(TiledRefine, ATileWhoseCellsSpanNoArea_AddsNoTriangle) {
    // The last tile (columns 20-21) has data only on its shared side, column 20.
    const HeightGrid grid = test::makeGrid(22, 15, [](int row, int col) {
        return col == 21 ? kNoData : 50.0 + 0.5 * row * col + (row % 2);
    });
    const RefineResult result = refine(grid, tiled(0.25, 20));
    expectConforming(result.mesh);
    const test::CoverageCheck check = test::checkCoverage(result.mesh, grid, 1);
    EXPECT_LE(check.maxError, 0.25 + 1e-6);
    EXPECT_EQ(check.uncoveredValid, 0U);
    EXPECT_EQ(result.uncoveredCells, 0U); // the side's cells, covered by the tile before
}

TEST(TiledRefine, TheUncoveredCellsReported_AreTheCellsNoTileCovers) {
    // Regression: tiles reported a side cell uncovered when its owner (the tile below or to
    // the right) had no triangle over it although the tile before did (Mt Hood in tiles of 16:
    // 69 cells reported, none uncovered). Peninsulas and holes across sides, small tiles, both
    // refined and full resolution, against the scan that shares no code with the refiner.
    for (const std::size_t tileSize : {3U, 5U, 8U}) {
        for (std::uint32_t seed = 1; seed <= 3; ++seed) {
            SCOPED_TRACE("tile size " + std::to_string(tileSize) + ", seed " +
                         std::to_string(seed));
            const HeightGrid grid = test::shoreWithPeninsulas(seed);
            for (const bool everyCell : {false, true}) {
                Tiled options = tiled(1.0, tileSize);
                if (everyCell) {
                    options.maxError.reset();
                    options.everyCell = true;
                }
                const RefineResult result = refine(grid, options);
                const test::CoverageCheck check = test::checkCoverage(result.mesh, grid, 1);
                EXPECT_EQ(result.uncoveredCells, check.uncoveredValid);
                EXPECT_LE(check.maxError, 1.0 + 1e-6);
            }
        }
    }
}

/// Tiles shared by threads of this process through a queue, a stand-in for MPI ranks: the
/// coordinator queues the tiles in reverse order, so that their TINs come back out of order
/// (all at once: no bound on the early tiles).
class ThreadTiles {
public:
    class Side final : public TileDistribution {
    public:
        Side(ThreadTiles& shared, bool coordinates)
            : m_shared(&shared), m_coordinates(coordinates) {}
        [[nodiscard]] bool coordinates() const override { return m_coordinates; }
        void gather(std::size_t tileCount,
                    const std::function<void(std::size_t, std::vector<std::byte>)>& take,
                    const std::function<bool()>&, std::uint64_t) override {
            std::unique_lock lock(m_shared->m_mutex);
            for (std::size_t tile = tileCount; tile-- > 0;)
                m_shared->m_tiles.push_back(tile);
            m_shared->m_changed.notify_all();
            for (std::size_t taken = 0; taken < tileCount; ++taken) {
                m_shared->m_changed.wait(lock, [&] { return !m_shared->m_results.empty(); });
                auto [tile, bytes] = std::move(m_shared->m_results.front());
                m_shared->m_results.pop_front();
                m_shared->m_order.push_back(tile);
                take(tile, std::move(bytes));
            }
            m_shared->m_stop = true;
            m_shared->m_changed.notify_all();
        }
        void serve(const std::function<std::vector<std::byte>(std::size_t)>& refine) override {
            std::unique_lock lock(m_shared->m_mutex);
            for (;;) {
                m_shared->m_changed.wait(
                    lock, [&] { return m_shared->m_stop || !m_shared->m_tiles.empty(); });
                if (m_shared->m_tiles.empty())
                    return;
                const std::size_t tile = m_shared->m_tiles.front();
                m_shared->m_tiles.pop_front();
                lock.unlock();
                std::vector<std::byte> bytes = refine(tile);
                lock.lock();
                m_shared->m_results.emplace_back(tile, std::move(bytes));
                m_shared->m_changed.notify_all();
            }
        }

    private:
        ThreadTiles* m_shared;
        bool m_coordinates;
    };

    /// The tiles in the order their TINs came back.
    [[nodiscard]] const std::vector<std::size_t>& order() const { return m_order; }

private:
    std::mutex m_mutex;
    std::condition_variable m_changed;
    std::deque<std::size_t> m_tiles;
    std::deque<std::pair<std::size_t, std::vector<std::byte>>> m_results;
    std::vector<std::size_t> m_order;
    bool m_stop = false;
};

TEST(TiledRefine, TilesRefinedElsewhere_OutOfOrder_GiveTheOneProcessTin) {
    const HeightGrid grid = test::roughTerrain(90, 70, 5);
    const RefineResult alone = refine(grid, tiled(1.0, 20, 1));

    ThreadTiles shared;
    ThreadTiles::Side coordinator(shared, true);
    std::vector<ThreadTiles::Side> others(2, ThreadTiles::Side(shared, false));
    std::vector<RefineResult> served(others.size());
    std::vector<std::thread> threads;
    for (std::size_t k = 0; k < others.size(); ++k)
        threads.emplace_back([&, k] {
            Tiled options = tiled(1.0, 20, 1);
            options.distribution = &others[k];
            served[k] = refine(grid, options);
        });
    Tiled options = tiled(1.0, 20, 1);
    options.distribution = &coordinator;
    const RefineResult joined = refine(grid, options);
    for (std::thread& thread : threads)
        thread.join();

    EXPECT_FALSE(std::is_sorted(shared.order().begin(), shared.order().end()));
    EXPECT_EQ(joined.mesh.vertices, alone.mesh.vertices);
    EXPECT_EQ(joined.mesh.sourceIndex, alone.mesh.sourceIndex);
    EXPECT_EQ(joined.mesh.triangles, alone.mesh.triangles);
    EXPECT_EQ(joined.mesh.neighbours, alone.mesh.neighbours);
    EXPECT_EQ(joined.maxError, alone.maxError);
    EXPECT_EQ(joined.rmse, alone.rmse);
    for (const RefineResult& result : served)
        EXPECT_EQ(result.mesh.triangleCount(), 0U); // the coordinator has the TIN
}

TEST(TiledRefine, ASinkGetsEveryTileInOrder_TheJoinedTinsTriangles) {
    const HeightGrid grid = test::roughTerrain(70, 50, 4);
    const RefineResult joined = refine(grid, tiled(1.0, 20));
    std::vector<std::size_t> order;
    std::vector<std::array<Point2, 3>> triangles;
    Tiled options = tiled(1.0, 20);
    options.tileSink = [&](std::size_t tile, TinMesh tin) {
        order.push_back(tile);
        for (std::size_t v = 0; v < tin.vertexCount(); ++v) // the grid's cells, not the tile's
            ASSERT_EQ(xy(tin.vertices[v]), grid.cellCentre(std::uint64_t{tin.sourceIndex[v]}));
        for (std::size_t t = 0; t < tin.triangleCount(); ++t)
            triangles.push_back({xy(tin.vertices[tin.triangles[3 * t]]),
                                 xy(tin.vertices[tin.triangles[3 * t + 1]]),
                                 xy(tin.vertices[tin.triangles[3 * t + 2]])});
    };
    const RefineResult sunk = refine(grid, options);
    EXPECT_EQ(sunk.mesh.triangleCount(), 0U);
    EXPECT_EQ(order, (std::vector<std::size_t>{0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11})); // 4 x 3
    std::vector<std::array<Point2, 3>> expected;
    for (std::size_t t = 0; t < joined.mesh.triangleCount(); ++t)
        expected.push_back({xy(joined.mesh.vertices[joined.mesh.triangles[3 * t]]),
                            xy(joined.mesh.vertices[joined.mesh.triangles[3 * t + 1]]),
                            xy(joined.mesh.vertices[joined.mesh.triangles[3 * t + 2]])});
    EXPECT_EQ(triangles, expected); // tile after tile, as the join keeps them
    EXPECT_EQ(sunk.maxError, joined.maxError);
    EXPECT_EQ(sunk.coveredCells, joined.coveredCells);
}

TEST(TileRefinement, PackedAndUnpacked_TheSame_ACutMessageRefused) {
    detail::TileRefinement tile;
    tile.mesh = refine(test::roughTerrain(30, 20, 9), test::validatedOptions(1.0)).mesh;
    tile.maxError = 0.75;
    tile.sumSquares = 12.5;
    tile.validCells = 600;
    tile.coveredCells = 598;
    tile.levels = 7;
    const std::vector<std::byte> bytes = detail::packTile(tile);
    const detail::TileRefinement back = detail::unpackTile(bytes);
    EXPECT_EQ(back.mesh.vertices, tile.mesh.vertices);
    EXPECT_EQ(back.mesh.sourceIndex, tile.mesh.sourceIndex);
    EXPECT_EQ(back.mesh.triangles, tile.mesh.triangles);
    EXPECT_EQ(back.mesh.neighbours, tile.mesh.neighbours);
    EXPECT_EQ(back.maxError, 0.75);
    EXPECT_EQ(back.sumSquares, 12.5);
    EXPECT_EQ(back.validCells, 600U);
    EXPECT_EQ(back.coveredCells, 598U);
    EXPECT_EQ(back.levels, 7U);
    for (const std::size_t cut :
         {std::size_t{0}, std::size_t{5}, bytes.size() / 2, bytes.size() - 1}) {
        const std::vector<std::byte> part(bytes.begin(),
                                          bytes.begin() + static_cast<std::ptrdiff_t>(cut));
        EXPECT_THROW(static_cast<void>(detail::unpackTile(part)), Error) << cut << " bytes";
    }
    std::vector<std::byte> longer = bytes;
    longer.push_back(std::byte{0});
    EXPECT_THROW(static_cast<void>(detail::unpackTile(longer)), Error);
}

TEST(TiledRefine, APointOrTriangleLimit_SharedAmongTheTiles_HoldsForTheWhole) {
    // A nodata block over the first tiles: the shares follow the valid cells each tile owns.
    const HeightGrid rough = test::roughTerrain(97, 83, 7);
    const HeightGrid grid = test::makeGrid(97, 83, [&](int row, int col) {
        return row < 30 && col < 50 ? kNoData : double{rough.z[row * 97 + col]};
    });
    const RefineResult free = refine(grid, tiled(2.0, 40));
    for (const bool points : {true, false}) {
        SCOPED_TRACE(points ? "point limit" : "triangle limit");
        Tiled options = tiled(2.0, 40);
        const std::size_t limit =
            (points ? free.mesh.vertexCount() : free.mesh.triangleCount()) * 2 / 3;
        if (points)
            options.maxPoints = limit;
        else
            options.maxTriangles = limit;
        const RefineResult result = refine(grid, options);
        const std::size_t count = points ? result.mesh.vertexCount() : result.mesh.triangleCount();
        EXPECT_LE(count, limit);
        EXPECT_GT(count, limit / 2);
        EXPECT_EQ(result.stop, points ? RefineStop::PointLimit : RefineStop::TriangleLimit);
        expectConforming(result.mesh);
        expectSidesFromTheirCells(result.mesh, grid, 40, 2.0);
        const test::CoverageCheck check = test::checkCoverage(result.mesh, grid, 1);
        EXPECT_EQ(check.uncoveredValid, 0U);
        EXPECT_GT(check.maxError, 2.0); // stopped by the limit before the error
    }
    // A share below what a tile's hull and sides keep: refused, not passed.
    Tiled tooFew = tiled(2.0, 40);
    tooFew.maxPoints = 40;
    EXPECT_THROW(refine(grid, tooFew), InvalidInputError);
}

Tiled everyCell(std::size_t tileSize, unsigned threads = 1) {
    Tiled options = tiled(0.0, tileSize, threads);
    options.maxError.reset();
    options.everyCell = true;
    return options;
}

TEST(TiledRefine, EveryCellInTiles_EachValidCellAVertex_OneConformingTin) {
    // Full resolution in tiles: every valid cell a vertex, each tile exactly
    // Delaunay (validated), the tiles joined without cracks; nodata across sides, an open hole
    // and filled single cells, a last tile one cell wide.
    const HeightGrid grid = test::makeGrid(42, 46, [](int row, int col) {
        if ((row - 29.5) * (row - 29.5) + (col - 20.0) * (col - 20.0) < 30.0)
            return kNoData;
        if ((row * 7 + col * 3) % 97 == 0)
            return kNoData;
        return 100.0 + 10.0 * std::sin(row * 0.3) * std::cos(col * 0.25) + 0.1 * (row % 3);
    });
    std::size_t validCells = 0;
    for (std::size_t cell = 0; cell < grid.cellCount(); ++cell)
        validCells += grid.isValid(cell) ? 1U : 0U;
    for (const unsigned threads : {1U, 2U}) {
        SCOPED_TRACE("threads " + std::to_string(threads));
        const RefineResult result = refine(grid, everyCell(20, threads));
        const TinMesh& mesh = result.mesh;
        expectConforming(mesh);
        EXPECT_TRUE(result.validated);
        EXPECT_EQ(mesh.vertexCount(), validCells);
        std::set<std::uint32_t> cells(mesh.sourceIndex.begin(), mesh.sourceIndex.end());
        EXPECT_EQ(cells.size(), validCells);
        for (std::size_t v = 0; v < mesh.vertexCount(); ++v) {
            const Point2 centre = grid.cellCentre(std::uint64_t{mesh.sourceIndex[v]});
            EXPECT_EQ(xy(mesh.vertices[v]), centre);
            EXPECT_EQ(mesh.vertices[v].z, double{grid.z[mesh.sourceIndex[v]]});
        }
        const test::CoverageCheck check = test::checkCoverage(mesh, grid, 1);
        EXPECT_EQ(check.maxError, 0.0);
        EXPECT_EQ(check.uncoveredValid, 0U);
        EXPECT_EQ(check.coveredOpenHoleCells, 0U);
        EXPECT_EQ(result.maxError, 0.0);
        EXPECT_GT(result.openHoleCells, 0U);
    }
}

TEST(TiledRefine, EveryCellInTiles_TheSameTinAsOneTile_WhereTheGridIsFull) {
    // A grid without nodata: its tiles' TINs together cover its rectangle with two triangles a
    // cell, as the whole grid's Delaunay TIN does.
    const HeightGrid grid = test::roughTerrain(37, 29, 5);
    const RefineResult tiles = refine(grid, everyCell(8));
    expectConforming(tiles.mesh);
    EXPECT_EQ(tiles.mesh.vertexCount(), grid.cellCount());
    EXPECT_EQ(tiles.mesh.triangleCount(), 2U * 36U * 28U);
    EXPECT_DOUBLE_EQ(areaSum(tiles.mesh), 36.0 * 28.0);
}

/// Each triangle of `mesh` as the cells of its corners (sourceIndex), from its smallest.
std::vector<std::array<std::uint32_t, 3>> cellTriangles(const TinMesh& mesh) {
    std::vector<std::array<std::uint32_t, 3>> triangles;
    for (std::size_t t = 0; t < mesh.triangleCount(); ++t) {
        std::array<std::uint32_t, 3> cells{};
        for (std::size_t corner = 0; corner < 3; ++corner)
            cells[corner] = mesh.sourceIndex[mesh.triangles[3 * t + corner]];
        std::rotate(cells.begin(), std::min_element(cells.begin(), cells.end()), cells.end());
        triangles.push_back(cells);
    }
    std::sort(triangles.begin(), triangles.end());
    return triangles;
}

TEST(TiledRefine, ARotatedGrid_InTiles_TheTinOfItsPixelFrame_AtTheCellsCentres) {
    // Tiles of a rotated grid are refined in its pixel frame and put at the cells' centres:
    // the TIN of the same cells north-up (or bottom-up, as the determinant's sign says), each
    // vertex at its cell's rotated centre, conforming, and within the bound there too.
    HeightGrid grid = test::roughTerrain(61, 47, 13);
    grid.z[grid.cellCount() / 2] = static_cast<float>(kNoData);
    const std::array<std::array<double, 6>, 3> rotations{{
        {500000.0, 0.8, 0.6, 4.0e6, 0.6, -0.8}, // square pixels turned, determinant -1
        {500000.0, 0.8, -0.6, 4.0e6, 0.6, 0.8}, // determinant +1
        {-12.5, 2.0, 0.5, 40.0, 0.25, -1.5},    // sheared, rectangular pixels
    }};
    for (const auto& rotation : rotations) {
        SCOPED_TRACE("geotransform " + std::to_string(rotation[1]) + " " +
                     std::to_string(rotation[2]) + " " + std::to_string(rotation[5]));
        HeightGrid upright = grid;
        const double determinant = rotation[1] * rotation[5] - rotation[2] * rotation[4];
        upright.geoTransform = {0.0, 1.0, 0.0, 0.0, 0.0, determinant < 0.0 ? -1.0 : 1.0};
        HeightGrid rotated = grid;
        rotated.geoTransform = rotation;
        const RefineResult expected = refine(upright, tiled(1.0, 16));
        for (const unsigned threads : {1U, 2U}) {
            const RefineResult result = refine(rotated, tiled(1.0, 16, threads));
            EXPECT_EQ(cellTriangles(result.mesh), cellTriangles(expected.mesh));
            EXPECT_EQ(result.mesh.sourceIndex, expected.mesh.sourceIndex);
            EXPECT_EQ(result.maxError, expected.maxError);
            EXPECT_EQ(result.uncoveredCells, 0U);
            expectConforming(result.mesh);
            for (std::size_t v = 0; v < result.mesh.vertexCount(); ++v)
                EXPECT_EQ(xy(result.mesh.vertices[v]),
                          rotated.cellCentre(std::uint64_t{result.mesh.sourceIndex[v]}));
            // Measured again in the CRS, by the scan that shares no code with the refiner:
            // cells on the TIN's outer edges may be rounded just outside it, never off the bound.
            const test::CoverageCheck check = test::checkCoverage(result.mesh, rotated, 1);
            EXPECT_LE(check.maxError, 1.0 + 1e-6);
            EXPECT_EQ(check.coveredOpenHoleCells, 0U);
        }
    }
}

TEST(TiledRefine, RefusesWhatTilesCannotDo) {
    const HeightGrid grid = test::roughTerrain(30, 30, 3);
    EXPECT_THROW(refine(grid, tiled(1.0, 1)), InvalidInputError);
    Tiled noError = tiled(1.0, 16);
    noError.maxError.reset();
    noError.maxPoints = 100;
    EXPECT_THROW(refine(grid, noError), InvalidInputError);
    // Tiles with the cells at positions of the caller's own take TileOptions::cellPositions:
    // refine() at positions has no tile options to be given.
    ThreadTiles shared;
    ThreadTiles::Side coordinator(shared, true);
    Tiled untiled = tiled(1.0, 16);
    untiled.tileSize = 0;
    untiled.distribution = &coordinator;
    EXPECT_THROW(refine(grid, untiled), InvalidInputError);
    Tiled everyCellUntiled = everyCell(16);
    everyCellUntiled.tileSize = 0;
    EXPECT_THROW(refine(grid, everyCellUntiled), InvalidInputError);
    Tiled everyCellWithError = everyCell(16);
    everyCellWithError.maxError = 1.0;
    EXPECT_THROW(refine(grid, everyCellWithError), InvalidInputError);
}

} // namespace
} // namespace terratin

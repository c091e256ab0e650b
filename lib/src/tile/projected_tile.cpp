#include "projected_tile.hpp"

#include "one_tile.hpp"
#include "placed_tile.hpp"
#include "tile_cells.hpp"
#include "tile_ring.hpp"

#include "../parallel/round_workers.hpp"
#include "../refine/cell_completion.hpp"
#include "../refine/greedy_refiner.hpp"

#include "terratin/constrain/constrained_validation.hpp"
#include "terratin/error.hpp"
#include "terratin/triangulate/mesh_filter.hpp"
#include "terratin/triangulate/triangulate.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <string_view>
#include <utility>

namespace terratin::detail {

namespace {

/// The tile's first TIN at its positions: every valid cell with options.everyCell, else the
/// refiner's, from the ring's cells and the valid cells on no side (the sides' other cells are
/// decided by the ring: kept out of the refiner as cells without data).
TinMesh firstTin(const PlacedTile& tile, const TileRing& ring, const TiledRefineOptions& options,
                 RoundWorkers& workers, const ProgressCallback& progress, TileRefinement& result) {
    const HeightGrid& grid = tile.read.grid;
    if (options.everyCell) {
        std::vector<Point3> points;
        std::vector<std::uint32_t> cellOf;
        for (std::uint32_t cell = 0; cell < grid.cellCount(); ++cell)
            if (grid.isValid(cell)) {
                points.push_back({tile.at[cell].x, tile.at[cell].y, double{grid.z[cell]}});
                cellOf.push_back(cell);
            }
        TriangulationOptions triangulation;
        triangulation.threads = workers.size();
        TinMesh mesh = triangulate(points, triangulation).mesh;
        for (std::uint32_t& source : mesh.sourceIndex)
            source = cellOf[source];
        return mesh;
    }
    HeightGrid refined = grid;
    CellFlags flags = tile.read.flags;
    std::vector<std::uint8_t> inRing(grid.cellCount(), 0);
    for (const std::uint32_t cell : ring.cells())
        inRing[cell] = 1;
    for (std::uint32_t cell = 0; cell < grid.cellCount(); ++cell)
        if (ring.onSide(cell) && inRing[cell] == 0) {
            refined.z[cell] = std::numeric_limits<float>::quiet_NaN();
            flags[cell] |= kCellNoData;
        }
    GreedyRefiner refiner(refined, tile.at, flags, options, workers);
    refiner.setSeedCells(ring.cells());
    refiner.run(progress);
    copyRefinerCounts(refiner, result);
    result.stop = refiner.stop();
    return refiner.extractInCellOrder();
}

/// The cells still over the bound, or in a triangle over an open hole, inserted into the tile's
/// TIN constrained to its ring (completeWithCells, with `rules`' cells): the triangles outside
/// the ring are dropped and their cells not measured, and a side cell goes in only where it
/// lies strictly inside the ring, where it is this tile's alone.
Completion completeInRing(const PlacedTile& placed, const TileRing& ring, ConstrainedTin& tin,
                          CompletionRules rules, const TiledRefineOptions& options,
                          unsigned threads, const ProgressCallback& progress) {
    const HeightGrid& grid = placed.read.grid;
    const std::vector<std::uint8_t> insideSides = sideCellsInside(ring, grid);
    rules.outsideArea = [frameSign = placed.frameSign](const ConstrainedTin& constrained) {
        return trianglesOutsideRing(constrained, frameSign);
    };
    rules.insertable = [&](std::size_t cell) {
        return !ring.onSide(static_cast<std::uint32_t>(cell)) || insideSides[cell] != 0;
    };
    rules.coverStrandedVertices = true;
    rules.keepCellErrors = true;
    return completeWithCells(grid, placed.at, tin, rules, options, threads, progress);
}

/// RefineOptions::validate's check of a tile's TIN: throws Error naming the first problem when
/// it is not constrained Delaunay.
void checkConstrainedDelaunay(const ConstrainedTin& tin) {
    const ConstrainedValidation validation = validateConstrainedDelaunay(tin);
    if (!validation.ok())
        throw Error("Refiner: a tile's TIN is not constrained Delaunay: " +
                    (validation.problems.empty() ? std::string("(no detail)")
                                                 : validation.problems.front()));
}

/// For each of `cells` (each a vertex of `mesh`, ascending), 0 when a triangle that `drop`
/// keeps uses its vertex (a vertex's error), else NaN: full resolution's measure.
std::vector<double> verticesKept(const TinMesh& mesh, const std::vector<std::uint8_t>& drop,
                                 const std::vector<std::size_t>& cells) {
    std::vector<std::uint8_t> used(mesh.vertexCount(), 0);
    for (std::size_t t = 0; t < mesh.triangleCount(); ++t)
        if (drop[t] == 0)
            for (std::size_t i = 0; i < 3; ++i)
                used[mesh.triangles[3 * t + i]] = 1;
    std::vector<double> squared(cells.size(), std::numeric_limits<double>::quiet_NaN());
    for (std::size_t v = 0; v < mesh.vertexCount(); ++v) {
        const auto at = std::lower_bound(cells.begin(), cells.end(), mesh.sourceIndex[v]);
        if (used[v] != 0 && at != cells.end() && *at == mesh.sourceIndex[v])
            squared[static_cast<std::size_t>(at - cells.begin())] = 0.0;
    }
    return squared;
}

/// `progress` for a part of the tile's work, from `start` for `share` of it.
ProgressCallback partOf(const ProgressCallback& progress, double start, double share) {
    if (!progress)
        return {};
    return [progress, start, share](double fraction, std::string_view message) {
        return progress(start + share * fraction, message);
    };
}

/// The tile's figures from each valid cell's squared error in its kept triangles (NaN: none).
void countFromErrors(const std::vector<std::size_t>& cells, const std::vector<double>& squared,
                     const HeightGrid& grid, bool topShared, bool leftShared, UnownedSides unowned,
                     TileRefinement& result) {
    const auto width = static_cast<std::size_t>(grid.width);
    const auto height = static_cast<std::size_t>(grid.height);
    for (std::size_t i = 0; i < cells.size(); ++i) {
        const std::size_t cell = cells[i];
        const bool covered = !std::isnan(squared[i]);
        const bool later = unowned(cell, width, height);
        if (!later && covered) {
            ++result.coveredCells;
            result.sumSquares += squared[i];
        }
        const bool shared = (topShared && cell / width == 0) || (leftShared && cell % width == 0);
        if (later && covered)
            result.coveredForLaterTiles.push_back({static_cast<std::uint32_t>(cell), squared[i]});
        else if (!later && shared && !covered)
            result.uncoveredSharedSides.push_back(static_cast<std::uint32_t>(cell));
    }
}

} // namespace

std::vector<std::uint32_t> keptProjectedSideCells(CellSource& cells, const TileGrid& tiles,
                                                  std::size_t tile,
                                                  const TiledRefineOptions& options) {
    const PlacedTile placed = placeTile(cells, tiles, tile, options);
    std::vector<std::uint32_t> kept;
    for (const std::vector<std::uint32_t>& side :
         keptSides(placed, options, static_cast<std::size_t>(cells.width()),
                   static_cast<std::size_t>(cells.height())))
        kept.insert(kept.end(), side.begin(), side.end());
    std::sort(kept.begin(), kept.end());
    kept.erase(std::unique(kept.begin(), kept.end()), kept.end());
    return kept;
}

TileRefinement refineProjectedTile(CellSource& cells, const TileGrid& tiles, std::size_t tile,
                                   const TiledRefineOptions& options, RoundWorkers& workers,
                                   const ProgressCallback& progress) {
    const std::size_t tileRow = tile / tiles.tileColumns();
    const std::size_t tileColumn = tile % tiles.tileColumns();
    const PlacedTile placed = placeTile(cells, tiles, tile, options);
    const HeightGrid& grid = placed.read.grid;
    const UnownedSides unowned = tiles.unownedSidesOf(tile);
    TileRefinement result;
    countCells(placed.read.flags, placed.width(), placed.height(), unowned, result);

    std::vector<std::size_t> validCells;
    CompletionRules rules;
    for (std::size_t cell = 0; cell < grid.cellCount(); ++cell) {
        if (grid.isValid(cell))
            validCells.push_back(cell);
        else if ((placed.read.flags[cell] & kCellOpenHole) != 0)
            rules.openHoleCells.push_back(cell);
    }
    if (!validCellsSpanArea(grid)) { // no triangle: every shared side cell uncovered
        countFromErrors(
            validCells,
            std::vector<double>(validCells.size(), std::numeric_limits<double>::quiet_NaN()), grid,
            tileRow > 0, tileColumn > 0, unowned, result);
        return result;
    }
    // At full resolution every valid cell is a vertex already: only the holes are located.
    if (!options.everyCell)
        rules.measuredCells = validCells;
    const TileRing ring(placed, keptSides(placed, options, static_cast<std::size_t>(cells.width()),
                                          static_cast<std::size_t>(cells.height())));
    TinMesh mesh = firstTin(placed, ring, options, workers, partOf(progress, 0.0, 0.8), result);
    checkTheShares(mesh, options, tileRow, tileColumn);
    ConstrainedTin tin = constrainToRing(std::move(mesh), ring, grid.cellCount());

    const Completion completion = completeInRing(placed, ring, tin, std::move(rules), options,
                                                 workers.size(), partOf(progress, 0.8, 0.2));
    if (completion.limitReached && result.stop == RefineStop::ErrorReached)
        result.stop = options.maxPoints ? RefineStop::PointLimit : RefineStop::TriangleLimit;
    if (options.validate)
        checkConstrainedDelaunay(tin);
    const std::vector<double> squaredErrors =
        options.everyCell ? verticesKept(tin.mesh, completion.drop, validCells)
                          : completion.squaredErrors;
    result.mesh = std::move(tin.mesh);
    dropTriangles(result.mesh, completion.drop);
    result.droppedTriangles = completion.holeTriangles;
    result.maxError = completion.maxError;
    countFromErrors(validCells, squaredErrors, grid, tileRow > 0, tileColumn > 0, unowned, result);
    return result;
}

} // namespace terratin::detail

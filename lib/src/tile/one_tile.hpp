#pragma once
/// @file
/// One tile of a tiled refinement (tile_refine.hpp): its cells read with a margin of
/// options.maxHole cells around them, which is all that decides which of its nodata cells lie
/// in open holes; its sides' vertices chosen from their cells alone; refined, its holes cut,
/// measured.

#include "tile_grid.hpp"
#include "tile_refinement.hpp"
#include "tiled_refine_options.hpp"

#include "terratin/progress.hpp"
#include "terratin/refine/refine.hpp"
#include "terratin/tile/cell_source.hpp"

#include <cstdint>
#include <span>
#include <vector>

namespace terratin::detail {

class RoundWorkers;

/// The largest error a tile side's vertices may leave on its cells (the tolerance given to
/// keptBorderCells), from that side's elevations alone: `maxError` less a margin for rounding,
/// since the tiles' planes evaluate the side's line in other operations than keptBorderCells,
/// and a cell exactly at the target along the line must not come out above it.
double sideTolerance(std::span<const float> side, double maxError);

/// The cells of a tile's four sides that become vertices within `maxError` (chosen from each
/// side's cells alone, with sideTolerance), side after side, as indices of `tile`'s cells; a
/// corner kept by both its sides comes twice.
std::vector<std::uint32_t> keptSideCells(const HeightGrid& tile, double maxError);

/// Refines tile `tile` (row-major among tiles.tileCount()) of `cells` with `options` (maxError
/// set, or everyCell; maxPoints and maxTriangles the tile's shares; tileSize, threads and
/// distribution ignored: the tile runs on `workers`). Throws InvalidInputError when a share is
/// below what the tile's hull and sides keep. With options.cellPositions, refineProjectedTile
/// (projected_tile.hpp) refines it.
TileRefinement refineOneTile(CellSource& cells, const TileGrid& tiles, std::size_t tile,
                             const TiledRefineOptions& options, RoundWorkers& workers,
                             const ProgressCallback& progress);

} // namespace terratin::detail

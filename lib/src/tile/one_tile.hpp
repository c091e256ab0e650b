#pragma once
/// @file
/// One tile of a tiled refinement (tile_refine.hpp): its cells read with a margin of
/// options.maxHole cells around them, which is all that decides which of its nodata cells lie
/// in open holes; its sides' vertices chosen from their cells alone; refined, its holes cut,
/// measured.

#include "tile_grid.hpp"
#include "tile_refinement.hpp"

#include "terratin/progress.hpp"
#include "terratin/refine/cell_source.hpp"
#include "terratin/refine/refine.hpp"

#include <span>

namespace terratin::detail {

class RoundWorkers;

/// The largest error a tile side's vertices may leave on its cells (the tolerance given to
/// keptBorderCells), from that side's elevations alone: `maxError` less a margin for rounding,
/// since the tiles' planes evaluate the side's line in other operations than keptBorderCells,
/// and a cell exactly at the target along the line must not come out above it.
double sideTolerance(std::span<const float> side, double maxError);

/// Refines tile `tile` (row-major among tiles.tileCount()) of `cells` with `options` (maxError
/// set; tileSize, threads and distribution ignored: the tile runs on `workers`).
TileRefinement refineOneTile(CellSource& cells, const TileGrid& tiles, std::size_t tile,
                             const RefineOptions& options, RoundWorkers& workers,
                             const ProgressCallback& progress);

} // namespace terratin::detail

#pragma once
/// @file
/// One tile of a tiled refinement whose cells lie at projected positions (TileOptions::
/// cellPositions: a geographic DEM refined in its UTM zone). The projection bends the tile's
/// sides, so the tiles no longer meet along straight hull edges: each tile is refined at its
/// cells' positions, its boundary, a ring through its sides' vertices (chosen from each side's
/// cells alone, projected_sides.hpp), is inserted as constraints, the triangles outside it
/// dropped, and the cells still over the bound inserted (refine/cell_completion.hpp).
/// Neighbouring tiles share the same chords, so their TINs join without cracks; each is a
/// constrained Delaunay TIN. docs/algorithms.md, "Tiles at projected positions", has the why.

#include "tile_grid.hpp"
#include "tile_refinement.hpp"
#include "tiled_refine_options.hpp"

#include "terratin/progress.hpp"
#include "terratin/refine/refine.hpp"
#include "terratin/tile/cell_source.hpp"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace terratin::detail {

class RoundWorkers;

/// The cells of tile `tile`'s four sides kept as vertices, as indices of the tile's cells (a
/// corner once), with options.cellPositions; every valid side cell with options.everyCell.
std::vector<std::uint32_t> keptProjectedSideCells(CellSource& cells, const TileGrid& tiles,
                                                  std::size_t tile,
                                                  const TiledRefineOptions& options);

/// refineOneTile for a grid whose cells lie at options.cellPositions (set). The figures are
/// those of refineOneTile; the tile's TIN is a constrained Delaunay TIN at the positions, its
/// vertices valid cells (sourceIndex the tile's cell index). Throws InvalidInputError as
/// refineOneTile does, and where a side's gap of no data bends too far (keptProjectedSideCells).
TileRefinement refineProjectedTile(CellSource& cells, const TileGrid& tiles, std::size_t tile,
                                   const TiledRefineOptions& options, RoundWorkers& workers,
                                   const ProgressCallback& progress);

} // namespace terratin::detail

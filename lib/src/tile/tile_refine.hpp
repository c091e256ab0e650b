#pragma once
/// @file
/// refineTiles (TileOptions::tileSize): the grid cut as TileGrid cuts it,
/// each tile refined on its own (one_tile.hpp), the TINs joined into one without cracks.
///
/// Seam-free by construction: the cells on a tile's four sides are never candidates; instead
/// each side gets, before any other insertion, the vertices keptBorderCells chooses from that
/// side's cells alone (border_profile.hpp), so the two tiles sharing a side put the same
/// vertices on it, and the TIN of each along the side is the same polyline. Within a tile the
/// TIN is exactly Delaunay; across a side it need not be.

#include "tiled_refine_options.hpp"

#include "terratin/progress.hpp"
#include "terratin/tile/cell_source.hpp"

namespace terratin::detail {

/// refineTiles (refine_tiles.hpp) once its input is checked.
RefineResult refineInTiles(CellSource& cells, const TiledRefineOptions& options,
                           const ProgressCallback& progress);

} // namespace terratin::detail

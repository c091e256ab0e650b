#pragma once
/// @file
/// refine() in tiles (RefineOptions::tileSize): the grid cut as TileGrid cuts it,
/// each tile refined on its own (one_tile.hpp), the TINs joined into one without cracks.
///
/// Seam-free by construction: the cells on a tile's four sides are never candidates; instead
/// each side gets, before any other insertion, the vertices keptBorderCells chooses from that
/// side's cells alone (border_profile.hpp), so the two tiles sharing a side put the same
/// vertices on it, and the TIN of each along the side is the same polyline. Within a tile the
/// TIN is exactly Delaunay; across a side it need not be.

#include "terratin/progress.hpp"
#include "terratin/refine/cell_source.hpp"
#include "terratin/refine/refine.hpp"

namespace terratin::detail {

/// refineTiles (refine.hpp) once its input is checked.
RefineResult refineInTiles(CellSource& cells, const RefineOptions& options,
                           const ProgressCallback& progress);

} // namespace terratin::detail

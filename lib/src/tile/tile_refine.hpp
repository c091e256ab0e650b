#pragma once
/// @file
/// refine() in tiles (RefineOptions::tileSize, issue 25): the grid cut as TileGrid cuts it,
/// each tile refined on its own, the TINs joined into one without cracks.
///
/// Seam-free by construction: the cells on a tile's four sides are never candidates; instead
/// each side gets, before any other insertion, the vertices keptBorderCells chooses from that
/// side's cells alone (border_profile.hpp), so the two tiles sharing a side put the same
/// vertices on it, and the TIN of each along the side is the same polyline. Within a tile the
/// TIN is exactly Delaunay; across a side it need not be.

#include "terratin/geometry/height_grid.hpp"
#include "terratin/progress.hpp"
#include "terratin/refine/refine.hpp"

namespace terratin::detail {

/// The largest error a tile side's vertices may leave on its cells (the tolerance given to
/// keptBorderCells): `maxError` less a margin for rounding, since the tiles' planes evaluate the
/// side's line in other operations than keptBorderCells, and a cell exactly at the target
/// along the line must not come out above it.
double sideTolerance(const HeightGrid& grid, double maxError);

/// The tiled refinement of `grid` with `options` (options.tileSize > 0, maxError set, no point
/// or triangle limit: refine() checks). RefineResult as refine()'s, with: maxError the largest
/// error each tile measured over its cells, in the pixel coordinates its scans used, and
/// checked against the target; rmse and coveredCells measured once over the joined TIN; the
/// counts of the strips, levels and insertions summed over the tiles (strips and levels:
/// the largest); validated when every tile was. A tile whose valid cells do not span an area
/// adds no triangle (its cells count as uncovered unless a neighbour covers them).
RefineResult refineInTiles(const HeightGrid& grid, const RefineOptions& options,
                           const ProgressCallback& progress);

} // namespace terratin::detail

#pragma once
/// @file
/// Puts a refined TIN in raster order: vertices by cell index, triangles by their
/// lowest-numbered corner.
///
/// The refiner numbers vertices in insertion order, which follows the errors and so jumps
/// across the raster, and the triangulator's triangles follow its allocation. Everything
/// after the refinement (the error check over every cell, dropping triangles over holes,
/// the writers) walks the triangles and reads their corners and cells; in raster order
/// those reads are nearly sequential instead of one cache miss each.

#include "terratin/triangulate/tin_mesh.hpp"

namespace terratin::detail {

/// Renumbers `mesh` (sourceIndex = cell index) as described above, on up to `threads`
/// threads; the TIN is unchanged.
void orderByCell(TinMesh& mesh, unsigned threads = 1);

} // namespace terratin::detail

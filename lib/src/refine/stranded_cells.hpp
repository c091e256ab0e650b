#pragma once
/// @file
/// Vertices stranded by the holes. The triangles over open holes are dropped once the
/// refinement is done, and a vertex that only they use goes with them: its valid cell is left
/// uncovered, although a TIN can often cover it (a cell hanging into a hole, with valid
/// neighbours beside it, is the corner of a small triangle over no hole cell). The refiner
/// never inserts those neighbours by itself: the triangles over the hole hold no valid cell
/// that is not a vertex, and the neighbours' own triangles are within the bound. Mt Hood has
/// such cells: one untiled, more in small tiles.
///
/// The cure: each stranded vertex's valid neighbours become vertices too, the refinement goes
/// on, and the check is repeated until it finds none to add.

#include "grid_scan.hpp"
#include "located_check.hpp"

#include "terratin/triangulate/tin_mesh.hpp"

#include <cstdint>
#include <span>
#include <vector>

namespace terratin::detail {

/// The cells to insert for the vertices of `mesh` (a whole triangulation of its hull,
/// sourceIndex the vertices' cells in `grid`) that every triangle marked in `drop` uses, and
/// no other: each one's 8 neighbouring cells that are valid, not vertices and not frozen, with
/// the triangle holding each (closed; found by a walk from the vertex) and the holes'
/// priority. Sorted by cell, each once; empty when there is none.
std::vector<CellToInsert> cellsBesideStrandedVertices(const TinMesh& mesh,
                                                      std::span<const std::uint8_t> drop,
                                                      const GridView& grid);

} // namespace terratin::detail

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
/// The completion of a constrained TIN (cell_completion.hpp) has the same cure, on its TIN.

#include "grid_scan.hpp"
#include "located_check.hpp"

#include "terratin/geometry/height_grid.hpp"
#include "terratin/triangulate/tin_mesh.hpp"

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <functional>
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

/// The same for a constrained TIN over the cells of `grid` (its vertices' sourceIndex, those
/// of no cell aside): the vertices that only the triangles marked in `overHoleOnly` use (with
/// no triangle that `drop` keeps), and each one's neighbouring cells that are valid, not
/// vertices and `insertable` (empty function: every one), each once, in cell order, with the
/// holes' priority and, as the triangle, one of the vertex's, where its insertion's walk starts.
std::vector<CellToInsert>
cellsBesideStrandedVertices(const HeightGrid& grid, const TinMesh& mesh,
                            std::span<const std::uint8_t> drop,
                            std::span<const std::uint8_t> overHoleOnly,
                            const std::function<bool(std::size_t cell)>& insertable);

/// Calls visit(cell, row, column) for the cells of the 3 x 3 block around `cell` (itself
/// included) that lie in a grid of `width` x `height`, row by row.
template <class Visit>
void forEachCellAround(std::uint32_t cell, std::int64_t width, std::int64_t height, Visit&& visit) {
    const std::int64_t row = static_cast<std::int64_t>(cell) / width;
    const std::int64_t column = static_cast<std::int64_t>(cell) % width;
    for (std::int64_t r = std::max<std::int64_t>(row - 1, 0); r <= std::min(row + 1, height - 1);
         ++r)
        for (std::int64_t c = std::max<std::int64_t>(column - 1, 0);
             c <= std::min(column + 1, width - 1); ++c)
            visit(static_cast<std::uint32_t>(r * width + c), r, c);
}

} // namespace terratin::detail

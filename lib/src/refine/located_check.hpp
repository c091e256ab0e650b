#pragma once
/// @file
/// The checks of error_check.hpp for a TIN whose coordinates are not an affine image of the
/// grid: the cells placed at given positions (a reprojection of their centres, say).
///
/// Notation: `positions[cell]` is where the cell's centre lies in the TIN's coordinates,
/// for every cell of the grid (nodata cells too: the holes are checked against them). The
/// pixel-space scans of grid_scan.hpp assume straight lines stay straight, which a
/// projection does not do; here every cell is instead located in the TIN, exactly: a walk
/// with exact orientation tests from the triangle of the previous cell, in raster order, so
/// each walk is a step or two. The TIN must be a triangulation of the convex hull of its
/// vertices and Delaunay (the visibility walk then ends, Edelsbrunner 1990), with no
/// triangle removed yet: holes are decided on it and their triangles passed as `drop`.
/// A cell on an edge is inside both triangles sharing it (closed triangles, as in
/// error_check.hpp). Elevations are interpolated in double in the TIN's coordinates, except
/// in a triangle whose corners are collinear in the grid: there a straight grid line was
/// bent by the map (or, straight, was rounded into a sliver), the plane means nothing, and
/// the elevation is the one along that line between the corners around the cell (see
/// CellWalker::elevation).

#include "error_check.hpp"
#include "grid_scan.hpp"

#include "terratin/geometry/point.hpp"
#include "terratin/triangulate/tin_mesh.hpp"

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace terratin::detail {

/// For each triangle of `mesh`: 1 when its closed triangle holds the position of a cell
/// flagged kCellOpenHole, else 0. Parallel over rows with up to `threads` threads.
std::vector<std::uint8_t> trianglesOverOpenHolesAt(const TinMesh& mesh, const GridView& grid,
                                                   std::span<const Point2> positions,
                                                   unsigned threads);

/// measureErrors for positions: every valid cell that is not flagged kCellVertex and lies in
/// a closed triangle t with drop[t] == 0 is measured against that triangle (against both on
/// a shared edge, counted once), and the vertices of the kept triangles count as covered
/// with error 0. `drop` as from trianglesOverOpenHolesAt (all zero for no hole).
ErrorMeasure measureErrorsAt(const TinMesh& mesh, std::span<const std::uint8_t> drop,
                             const GridView& grid, std::span<const Point2> positions,
                             unsigned threads);

/// A cell the refinement still has to insert, the triangle of `mesh` it lies in, and its
/// priority as a refinement candidate: its error there, +infinity over an open hole.
struct CellToInsert {
    std::uint32_t cell = 0;
    std::uint32_t triangle = 0;
    double priority = 0.0;
};

/// What one check of cellsToInsertAt passes to the next, so that the next looks only at the
/// cells whose triangle changed in between: a cell strictly inside a triangle that is still
/// there keeps its error and was not to be inserted (else its triangle would have been split),
/// and every cell inside a new triangle was inside one that changed. Cells on an edge are
/// always checked again (the triangle across may have changed).
struct CheckMemo {
    /// Per cell: 1 to skip it (its triangle is unchanged since the last check), else 0.
    std::span<const std::uint8_t> unchanged;
    /// Per cell: a triangle of the mesh near it, where its walk may start, or -1.
    std::span<const std::int32_t> near;
    /// Out, per cell checked: the triangle holding it strictly inside, or -1 (on an edge).
    /// Cells not checked are left as they are.
    std::span<std::int32_t> located;
};

/// The refiner's rule, checked exactly: for each triangle holding a valid non-vertex cell
/// farther than `threshold` from it, or holding both such a cell (at any error) and an open
/// hole's cell, its farthest such cell (ties: the lowest cell index). Sorted by cell index,
/// each cell once. Empty when the TIN meets the guarantee.
/// With `memo`, only the cells memo.unchanged does not mark are looked at, and memo.located
/// is filled (memo.unchanged and memo.near may be empty: every cell is checked).
std::vector<CellToInsert> cellsToInsertAt(const TinMesh& mesh, const GridView& grid,
                                          std::span<const Point2> positions, double threshold,
                                          unsigned threads, const CheckMemo* memo = nullptr);

} // namespace terratin::detail

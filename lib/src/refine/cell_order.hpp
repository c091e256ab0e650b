#pragma once
/// @file
/// The refined TIN taken out of the refiner's mesh in raster order: vertices by cell index,
/// triangles by their lowest-numbered corner.
///
/// The refiner numbers vertices in insertion order, which follows the errors and so jumps
/// across the raster, and its triangles follow its slot allocation. Everything after the
/// refinement (the error check over every cell, dropping triangles over holes, the writers)
/// walks the triangles and reads their corners and cells; in raster order those reads are
/// nearly sequential instead of one cache miss each. The order is also the output's: the
/// same TIN always comes out the same.

#include "refine_mesh.hpp"

#include "terratin/triangulate/tin_mesh.hpp"

#include <cstdint>
#include <span>
#include <vector>

namespace terratin::detail {

/// Vertex ids [first, end) in use.
struct VertexRange {
    VertexId first = 0;
    VertexId end = 0;
};

/// The triangles of `mesh` with the vertices of `ranges` (every vertex a triangle uses lies
/// in one), in raster order, sourceIndex = cell index (row * width + col). On up to
/// `threads` threads. With `slotOfTriangle`, sets it to the slot of each triangle. The arrays
/// have room for `spareVertices` more vertices (reserveRoom).
TinMesh extractInCellOrder(const RefineMesh& mesh, std::span<const RefineVertex> vertices,
                           std::span<const VertexRange> ranges, std::int64_t width,
                           unsigned threads, std::vector<TriId>* slotOfTriangle = nullptr,
                           std::size_t spareVertices = 0);

} // namespace terratin::detail

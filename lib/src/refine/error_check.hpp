#pragma once
/// @file
/// After the build: which triangles cover an open hole, and how far every covered valid cell
/// is from the TIN (the guarantee is measured, not assumed).

#include "grid_scan.hpp"

#include "terratin/triangulate/tin_mesh.hpp"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace terratin::detail {

/// For each triangle of `mesh` (sourceIndex = cell index): 1 when its closed triangle holds
/// the centre of a cell flagged kCellOpenHole (a pixel-collinear triangle: a cell on its
/// segment), else 0. Parallel over triangles with up to `threads` threads.
std::vector<std::uint8_t> trianglesOverOpenHoles(const TinMesh& mesh, const GridView& grid,
                                                 unsigned threads);

/// What the check measured.
struct ErrorMeasure {
    double maxError = 0.0;
    double sumSquares = 0.0;
    /// Valid cells inside a triangle (each once), vertices included.
    std::size_t coveredCells = 0;
};

/// Measures every valid cell inside a triangle of `mesh` against the triangle's plane: the
/// largest error over every closed triangle (a cell on an edge is measured in both), and the
/// sum of squares and count with each cell counted once (a cell on an edge shared by two
/// triangles belongs to the one that owns the edge, PixelTriangle::ownsSharedEdge). Vertex
/// cells are exact (error 0) and counted once each. Cells flagged kCellVertex that are not
/// vertices of `mesh` any more (removed with dropped triangles) are skipped.
ErrorMeasure measureErrors(const TinMesh& mesh, const GridView& grid, unsigned threads);

} // namespace terratin::detail

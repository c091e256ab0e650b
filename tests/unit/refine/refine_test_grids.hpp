#pragma once
// Grids for the refinement tests and a check of a TIN against a grid that shares no code with
// the refiner (CRS coordinates, exact point-in-triangle tests, barycentric interpolation).

#include "terratin/geometry/height_grid.hpp"
#include "terratin/refine/refine.hpp"
#include "terratin/triangulate/tin_mesh.hpp"

#include <cstddef>
#include <cstdint>
#include <functional>
#include <span>
#include <vector>

namespace terratin::test {

/// A width x height grid with z(row, col) (NaN = nodata) and geotransform (0, 1, 0, 0, 0, -1)
/// shifted so that cell centres are at (col + 0.5, -(row + 0.5)): north-up, y decreasing.
HeightGrid makeGrid(int width, int height, const std::function<double(int row, int col)>& z);

/// Options with `maxError`, `threads` and validation on, as most refinement tests want.
RefineOptions validatedOptions(double maxError, unsigned threads = 1);

/// Smooth hills plus deterministic pseudo-random noise (metres, 0..~300).
HeightGrid roughTerrain(int width, int height, std::uint32_t seed);

/// 48 x 40 cells: roughTerrain above row 24, a hole from row 24 down, and on row 24 single
/// valid cells hanging into it (peninsulas: the row above valid, their sides and below
/// nodata), the pattern that left a cell of Mt Hood uncovered (stranded_cells.hpp).
HeightGrid shoreWithPeninsulas(std::uint32_t seed);

/// What the independent check found.
struct CoverageCheck {
    double maxError = 0.0;
    /// Valid cells inside no triangle.
    std::size_t uncoveredValid = 0;
    /// Nodata cells inside a triangle, in each hole of more than `maxHole` cells in all.
    std::size_t coveredOpenHoleCells = 0;
};

/// Checks every cell of `grid` against every triangle of `mesh` holding its centre (closed,
/// exact orientation in CRS coordinates): the interpolated elevation in CRS coordinates.
/// With `positions` (one per cell), the cells lie there instead of at their centres.
CoverageCheck checkCoverage(const TinMesh& mesh, const HeightGrid& grid, std::size_t maxHole,
                            std::span<const Point2> positions = {});

/// EXPECTs every covered valid cell within maxError (plus 1e-6 for the rounding of the CRS
/// interpolation) and every valid cell covered.
void expectWithinError(const TinMesh& mesh, const HeightGrid& grid, double maxError);

/// EXPECTs no vertex of `mesh` strictly inside the circumcircle of any of its triangles
/// (exact, brute force): the triangles are Delaunay over the vertices even with some removed.
void expectEmptyCircumcircles(const TinMesh& mesh);

} // namespace terratin::test

#pragma once
/// @file
/// Terrain simplification: an error-bounded, exactly Delaunay TIN from a HeightGrid, by greedy
/// insertion in the manner of M. Garland & P. S. Heckbert, "Fast Polygonal Approximation of
/// Terrains and Height Fields" (CMU-CS-95-181, 1995), made parallel by refining vertical strips
/// of the raster at once (docs/algorithms.md, "The refiner", tells how).
///
/// Notation: a cell's error is |z(cell) - T(cell)|, the vertical distance between its
/// elevation and the TIN's linear interpolation T at its centre, in the grid's z units.
/// T is evaluated in double in pixel coordinates (col, row), where the cell centres are exact
/// integers; since the geotransform is affine, this is the same linear function as in CRS
/// coordinates (a recomputation from CRS coordinates differs only by rounding, ~1e-12 of z).

#include "terratin/geometry/height_grid.hpp"
#include "terratin/progress.hpp"
#include "terratin/triangulate/tin_mesh.hpp"
#include "terratin/triangulate/triangulate.hpp"

#include <cstddef>
#include <cstdint>
#include <functional>
#include <limits>
#include <optional>
#include <span>
#include <vector>

namespace terratin {

/// Most cells a grid may have for refine(): vertex ids are 32-bit and the triangulation needs
/// a few for itself. Also the largest point limit and hole size that mean anything.
inline constexpr std::uint64_t kMaxRefineCells = (std::uint64_t{1} << 32U) - 5;

/// How much to simplify. With no limit at all every valid cell becomes a vertex.
/// checkRefineOptions states the ranges.
struct RefineOptions {
    /// Target vertical tolerance E, z units, >= 0: refinement stops when every valid cell
    /// covered by the TIN is within E of it (error <= E; a cell exactly E away is kept out).
    std::optional<double> maxError;
    /// Stop before the TIN has more than this many vertices, 3 to kMaxRefineCells. The limit
    /// always holds: the refinement starts from the convex hull of the valid cells, so a limit
    /// below the hull's corner count is refused (InvalidInputError naming that count).
    std::optional<std::size_t> maxPoints;
    /// Stop before the TIN has more than this many triangles, 1 to 2 * kMaxRefineCells
    /// (counted before the triangles over holes are dropped, so the output has at most as
    /// many). The limit always holds: the hull's corners alone make (corners - 2) triangles,
    /// and a smaller limit is refused (InvalidInputError naming that count).
    std::optional<std::size_t> maxTriangles;
    /// Hardware threads for insertion and scans, 0 to kMaxThreads; 0 = all. The TIN does not
    /// depend on it.
    unsigned threads = 0;
    /// Vertical strips of the raster refined at once (the unit of parallel work, see the
    /// refiner); 0 chooses from the raster's width. Fixed by the raster, not the threads, so
    /// that the result does not depend on the thread count; 1 gives strict greedy insertion.
    std::size_t strips = 0;
    /// Nodata regions (8-connected) of at most this many cells may be covered by triangles;
    /// larger ones stay open: no triangle covers the centre of one of their cells. 0 to
    /// kMaxRefineCells.
    std::size_t maxHole = 1;
    /// Cover every hole (interpolate across nodata), ignoring maxHole.
    bool fillHoles = false;
    /// Return the TIN with its triangles over open holes (it covers the convex hull of the
    /// valid cells), for callers that change it before cutting the holes; the figures are
    /// measured as without. droppedTriangles still counts the triangles over holes.
    bool keepHoleTriangles = false;
    /// Measure the TIN over every valid cell at the end (maxError, rmse, coveredCells,
    /// uncoveredCells, validCells; a cell over maxError is an error). False skips that pass,
    /// leaving those figures at 0 (and droppedTriangles with keepHoleTriangles; without it the
    /// triangles over holes are still dropped and counted), for callers that change the TIN
    /// and measure what they make of it (the simplified constrained build).
    bool measure = true;
    /// Room left in the TIN's arrays for this many more vertices (TriangulationOptions::
    /// spareVertices), for callers that insert more.
    std::size_t spareVertices = 0;
    /// Run validateDelaunay on the TIN before the triangles over holes are dropped and throw
    /// terratin::Error when it is not exactly Delaunay (with tiles: each tile's TIN).
    bool validate = false;
};

/// Why refinement stopped.
enum class RefineStop {
    ErrorReached,  ///< every candidate within maxError (or every cell used)
    PointLimit,    ///< maxPoints reached
    TriangleLimit, ///< maxTriangles reached
};

/// The simplified TIN and how good it is, measured after the build over every valid cell.
struct RefineResult {
    /// Vertices: exact cell centres (HeightGrid::cellCentre) with the cells' elevations;
    /// sourceIndex[v] = the vertex's cell index (row * width + col). Triangles over holes are
    /// dropped (neighbour kNoNeighbour across them) and vertices only they used removed.
    TinMesh mesh;
    /// Largest error of a valid cell inside a kept triangle (checked cell by cell), z units.
    double maxError = 0.0;
    /// Root mean square of the errors of the covered valid cells (vertices count as 0). Summed
    /// in triangle order, which depends on the threads: may differ in the last bits.
    double rmse = 0.0;
    /// Valid cells inside a kept triangle (each counted once) and valid cells in none.
    std::size_t coveredCells = 0;
    std::size_t uncoveredCells = 0;
    /// Valid cells of the grid and nodata cells in holes left open (larger than maxHole).
    std::size_t validCells = 0;
    std::size_t openHoleCells = 0;
    /// Triangles dropped because they covered an open hole's cell centre.
    std::size_t droppedTriangles = 0;
    /// Vertices of the convex hull the refinement started from.
    std::size_t hullPoints = 0;
    /// Strips refined at once and levels of error they went down by; candidates deferred
    /// because their insertion reached past their strip (or pair of strips); points inserted
    /// by the pairs of neighbouring strips and by the sequential step (the rest went in within
    /// one strip).
    std::size_t strips = 0;
    std::size_t levels = 0;
    std::size_t deferredCandidates = 0;
    std::size_t pairInsertions = 0;
    std::size_t sharedInsertions = 0;
    /// With positions: passes of the exact completion that inserted cells the levels'
    /// approximate scans left above the target (0 without positions).
    std::size_t completionPasses = 0;
    RefineStop stop = RefineStop::ErrorReached;
    unsigned threads = 1;
    /// True when options.validate ran and passed.
    bool validated = false;
    /// Wall-clock seconds: greedy insertion, extraction and hole dropping, error check.
    double insertSeconds = 0.0;
    double extractSeconds = 0.0;
    double checkSeconds = 0.0;
    /// Bytes of the triangulation's triangles (with tiles, the sum over the tiles).
    std::size_t meshBytes = 0;
};

/// "error", "points" or "triangles".
const char* toString(RefineStop stop);

/// One byte per cell of `grid`: 1 for the nodata cells refine() with `options` leaves open
/// (8-connected nodata regions of more than options.maxHole cells; none with
/// options.fillHoles), else 0. O(cells).
std::vector<std::uint8_t> openHoleCells(const HeightGrid& grid, const RefineOptions& options);

/// Throws InvalidInputError, naming the option and its range, when an option is outside the
/// range its documentation states (maxError negative or not finite, maxPoints below 3,
/// maxTriangles below 1, a count above its bound, threads above kMaxThreads). refine() calls
/// it first; a caller that maps user input onto the options calls it to refuse bad values
/// before reading anything.
void checkRefineOptions(const RefineOptions& options);

/// Builds the simplified TIN of `grid`.
///
/// Starts from the convex hull of the valid cells (found from each row's first and last
/// valid cell), so every valid cell is covered from the start; then repeatedly inserts the
/// valid cell farthest from the TIN (ties: the lowest cell index), keeping the triangulation
/// exactly Delaunay (exact predicates, symbolic auxiliary triangle), and rescans only the
/// triangles an insertion created. A triangle that covers an open hole's cell and a valid
/// non-vertex cell is refined first, so that after its removal the hole's edge follows the
/// nodata. Postconditions: without a limit reached, every valid cell inside a kept triangle
/// is within maxError (checked, else Error); the undropped triangulation is exactly Delaunay
/// over the vertices; the same options give the same TIN for any thread count.
///
/// Throws InvalidInputError (options out of range, see checkRefineOptions; empty grid, no
/// valid cell, an infinite elevation, valid cells all collinear, more than kMaxRefineCells
/// cells, a point or triangle limit below what the hull needs), Cancelled when `progress`
/// returns false, Error when a check fails. Complexity: O(cells log points) expected for the
/// scans; memory: the grid, one byte per cell of flags, and O(points) for the triangulation.
RefineResult refine(const HeightGrid& grid, const RefineOptions& options,
                    const ProgressCallback& progress = {});

/// Throws InvalidInputError for a grid refine() cannot take: empty, elevations that do not
/// match its cells, more than kMaxRefineCells cells, an infinite elevation (NaN is nodata).
/// refine() and refineTiles (tile/refine_tiles.hpp) call it.
void checkRefineGrid(const HeightGrid& grid);

/// refine() with the TIN in other coordinates than the grid's: the vertex of cell c lies at
/// `positions[c]` (x, y; one entry per cell, nodata cells included, row-major), typically the
/// cell centres reprojected from a geographic CRS to a UTM zone. The map from pixels to
/// positions must be one-to-one and nearly affine at the scale of a cell (as a map
/// projection is), not affine: the TIN is Delaunay in the positions' coordinates, and its
/// straight edges are curves in the grid.
///
/// The levels choose their points with the pixel-space scans (an approximation here); then
/// every cell is located in the TIN exactly, at its position, and the cells still farther
/// than maxError (or in a triangle over an open hole) are inserted, pass after pass, until
/// none is left. The guarantee, the holes (no kept triangle holds the position of an open
/// hole's cell) and the error report are all measured at the positions, and the
/// postconditions of refine() hold there. Same exceptions as refine(), and
/// InvalidInputError when `positions` is empty, has not one entry per cell or holds a
/// non-finite value. Memory: 16 bytes per cell for `positions`, the caller's.
RefineResult refine(const HeightGrid& grid, std::span<const Point2> positions,
                    const RefineOptions& options, const ProgressCallback& progress = {});

} // namespace terratin

#pragma once
/// @file
/// The cells of a grid still over the error bound inserted into a constrained Delaunay TIN until
/// none is: the last step of a simplified constrained build (docs/algorithms.md, "Simplified
/// constrained TINs") and of a tile refined at projected positions (tile/projected_tile.hpp).
/// It is the refiner's rule (each triangle's worst cell, a triangle over an open hole split until
/// it covers no valid cell, the same limits) on a TIN whose constrained edges the refiner's own
/// mesh cannot hold: completion_check.hpp measures, insertVertices inserts. What is measured,
/// kept and insertable is the caller's: CompletionRules.

#include "terratin/constrain/constrained_tin.hpp"
#include "terratin/geometry/height_grid.hpp"
#include "terratin/geometry/point.hpp"
#include "terratin/progress.hpp"
#include "terratin/refine/refine.hpp"

#include <cstddef>
#include <cstdint>
#include <functional>
#include <span>
#include <vector>

namespace terratin::detail {

/// Where `cell` lies: positions[cell], or the grid's cell centre when `positions` is empty.
inline Point2 cellPosition(const HeightGrid& grid, std::span<const Point2> positions,
                           std::size_t cell) {
    return positions.empty() ? grid.cellCentre(static_cast<std::uint64_t>(cell)) : positions[cell];
}

/// Which cells a completion measures, which triangles it keeps, which cells it may insert.
struct CompletionRules {
    /// The valid cells the bound holds for, ascending; and the cells of open holes, which no
    /// kept triangle may cover, ascending.
    std::vector<std::size_t> measuredCells;
    std::vector<std::size_t> openHoleCells;
    /// Per triangle of the TIN: 1 outside the output's area (dropped, its cells not measured).
    /// Empty function: every triangle is in the area.
    std::function<std::vector<std::uint8_t>(const ConstrainedTin&)> outsideArea;
    /// Per triangle: 1 for a kept triangle whose cells are not measured (a replace area's flat
    /// triangles). Empty function: none.
    std::function<std::vector<std::uint8_t>(const ConstrainedTin&)> unmeasured;
    /// Whether a measured cell may become a vertex (empty function: every one). A cell it
    /// refuses is still measured: its error counts, and must be within the bound by other means.
    std::function<bool(std::size_t cell)> insertable;
    /// Called after each round of insertions (the replace rings flattened again).
    std::function<void(ConstrainedTin&)> afterInsertions;
    /// When every cell is within the bound, insert the valid cells beside each vertex that only
    /// triangles over open holes use, and go on, until there is none (a TIN refined without
    /// that step: a tile at projected positions).
    bool coverStrandedVertices = false;
    /// Keep each measured cell's squared error at the end (Completion::squaredErrors).
    bool keepCellErrors = false;
};

/// What the completion did and its last check measured.
struct Completion {
    /// Over the measured cells inside a kept triangle: the largest error, the root mean square
    /// error, and their count; measured cells in no kept triangle (outside the hull or in a
    /// triangle over an open hole).
    double maxError = 0.0;
    double rmse = 0.0;
    double sumSquares = 0.0;
    std::size_t coveredCells = 0;
    std::size_t uncoveredCells = 0;
    /// drop[t] = 1 for the triangles to remove: outside the area, or over an open hole's cell
    /// (holeTriangles of them only for that).
    std::vector<std::uint8_t> drop;
    std::size_t holeTriangles = 0;
    /// Checks of the whole TIN, and cells inserted.
    std::size_t passes = 0;
    std::size_t insertedCells = 0;
    /// The point or triangle limit stopped the insertions.
    bool limitReached = false;
    /// With CompletionRules::keepCellErrors: for each measured cell (in measuredCells' order)
    /// its squared error in the kept triangle holding it, NaN when none does.
    std::vector<double> squaredErrors;
};

/// Measures every cell of rules.measuredCells (at `positions`, or at the grid's cell centres
/// when empty) against `tin`; while cells are over options.maxError (when set), or lie in a
/// triangle over an open hole, inserts the worst insertable cell of each triangle
/// (insertVertices: constrained edges are never flipped) and measures again the cells of the
/// triangles that changed, then every cell once more before it stops. Stops at
/// options.maxPoints and maxTriangles. Calls `progress` before every check, and throws Cancelled
/// when it returns false. The result is the same for any number of `threads`.
Completion completeWithCells(const HeightGrid& grid, std::span<const Point2> positions,
                             ConstrainedTin& tin, const CompletionRules& rules,
                             const RefineOptions& options, unsigned threads,
                             const ProgressCallback& progress);

} // namespace terratin::detail

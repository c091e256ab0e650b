#pragma once
/// @file
/// Simplification with constraints (--max-error or --max-points with --breaklines, --clip,
/// --erase or --replace): the refiner's points, the constraints inserted into their TIN, then
/// the cells still over the bound inserted into the constrained TIN until none is
/// (docs/algorithms.md, "Simplified constrained TINs").

#include "breaklines.hpp"
#include "terratin/geometry/height_grid.hpp"
#include "terratin/pipeline/build_pipeline.hpp"
#include "terratin/progress.hpp"
#include "terratin/refine/refine.hpp"

#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace terratin::detail {

/// The simplified constrained TIN and what its check measured.
struct ConstrainedRefinement {
    ConstrainedBuild build;
    /// drop[t] = 1 for the triangles to remove: outside the clip area, inside an erase area, or
    /// over an open hole's cell.
    std::vector<std::uint8_t> drop;
    /// Over the valid cells measured (inside a kept triangle, not in a replace area): the
    /// largest error and the root mean square error; valid cells in a dropped hole triangle or
    /// outside the hull.
    double maxError = 0.0;
    double rmse = 0.0;
    std::size_t uncoveredCells = 0;
    std::size_t holeTriangles = 0;
    /// Cells of the holes left open (those of erase and replace areas are not holes).
    std::size_t openHoleCells = 0;
    /// Checks of the whole TIN, and cells inserted after the constraints.
    std::size_t passes = 0;
    std::size_t insertedCells = 0;
    /// The point or triangle limit stopped the insertions.
    bool limitReached = false;
};

/// `refined` (the refiner's TIN of `grid` with its triangles over holes, RefineOptions::
/// keepHoleTriangles; vertices at `positions` or at the cell centres when `positions` is empty;
/// the cells of erase and replace areas left out, leaveOutAreaCells) with the constraints of
/// `sources` inserted (addConstraints; z still missing from that TIN's surface), then every
/// valid cell outside the erase and replace areas and inside the clip area measured against the
/// constrained TIN: while cells are over options.refine->maxError, or lie in a triangle over an
/// open hole, the worst of each triangle is inserted (insertVertices: constrained edges are never
/// flipped) and the TIN measured again. Stops at the point and triangle limits. Fills the
/// constraint figures of `report`; calls `progress` (which may throw Cancelled) before every check.
ConstrainedRefinement refineWithConstraints(const HeightGrid& grid,
                                            std::span<const Point2> positions, TinMesh refined,
                                            const BuildOptions& options, ConstraintSources sources,
                                            BuildReport& report, const ProgressCallback& progress);

/// Sets the cells of `grid` inside an erase or replace polygon of `sources` to no data, before
/// the refiner runs: it spends no point where the output has none, or is flat. Cells lie at
/// `positions`, or at their centres when it is empty. Returns how many valid cells a replace
/// polygon held.
std::size_t leaveOutAreaCells(HeightGrid& grid, std::span<const Point2> positions,
                              const ConstraintSources& sources);

} // namespace terratin::detail

#include "constrained_refine.hpp"

#include "../parallel/parallel_for.hpp"
#include "../refine/cell_completion.hpp"
#include "../refine/valid_hull.hpp"
#include "constraint_areas.hpp"
#include "terratin/constrain/insert_constraints.hpp"

#include <cmath>
#include <limits>
#include <optional>

namespace terratin::detail {

namespace {

/// Which cells the bound holds for, and where the open holes are.
struct CellSets {
    /// The valid cells (the erase and replace areas' cells are no data by now,
    /// leaveOutAreaCells; the clip area is decided by the triangle holding the cell).
    std::vector<std::size_t> measuredCells;
    /// The open holes' cells that a triangle might cover (inside the TIN's hull or on it),
    /// and the count of all of them, for the report.
    std::vector<std::size_t> openHoleCells;
    std::size_t allOpenHoleCells = 0;
};

/// The corners of the refined TIN's hull, the convex hull of the valid cells (the
/// constraints are clipped to it, and only valid cells are inserted), counter-clockwise.
std::vector<Point2> tinHull(const HeightGrid& grid, std::span<const Point2> positions) {
    std::vector<Point2> corners;
    for (const std::uint32_t cell : validHullCells(grid, positions))
        corners.push_back(cellPosition(grid, positions, cell));
    return corners;
}

/// Whether the cell at `p` lies in an erase or replace polygon.
bool inLeftOutArea(Point2 p, const std::optional<PolygonSet>& erase,
                   const std::optional<PolygonSet>& replace) {
    return (erase && erase->holds(p)) || (replace && replace->holds(p));
}

CellSets cellSets(const HeightGrid& grid, std::span<const Point2> positions,
                  const RefineOptions& refineOptions, const std::optional<PolygonSet>& erase,
                  const std::optional<PolygonSet>& replace) {
    CellSets sets;
    sets.measuredCells.reserve(grid.cellCount()); // most cells: growing would copy them
    const std::vector<std::uint8_t> open = openHoleCells(grid, refineOptions);
    // An open hole's cell outside the hull stays outside every triangle: none is located.
    const std::vector<Point2> hull = tinHull(grid, positions);
    for (std::size_t cell = 0; cell < grid.cellCount(); ++cell) {
        // The erase and replace areas' cells are no data to the refiner, but no hole: the
        // TIN keeps its triangles there (flat ones), or the area drops them.
        if (open[cell] != 0) {
            const Point2 p = cellPosition(grid, positions, cell);
            if (!inLeftOutArea(p, erase, replace)) {
                ++sets.allOpenHoleCells;
                if (!outsideConvexPolygon(hull, p))
                    sets.openHoleCells.push_back(cell);
                continue;
            }
        }
        // A cell on a replace ring is on the lake's shore: the TIN's vertex there is the
        // ring's, at the lake's level, so the cell is not measured, as those inside are not.
        if (grid.isValid(cell) &&
            !(replace && replace->onRing(cellPosition(grid, positions, cell))))
            sets.measuredCells.push_back(cell);
    }
    return sets;
}

} // namespace

std::size_t leaveOutAreaCells(HeightGrid& grid, std::span<const Point2> positions,
                              const ConstraintSources& sources) {
    if (!sources.erase && !sources.replace)
        return 0;
    std::optional<PolygonSet> erase;
    std::optional<PolygonSet> replace;
    if (sources.erase)
        erase.emplace(*sources.erase);
    if (sources.replace)
        replace.emplace(*sources.replace);
    std::size_t replaced = 0;
    for (std::size_t cell = 0; cell < grid.cellCount(); ++cell) {
        if (!grid.isValid(cell))
            continue;
        const Point2 p = cellPosition(grid, positions, cell);
        if (replace && replace->holds(p))
            ++replaced;
        else if (!erase || !erase->holds(p))
            continue;
        grid.z[cell] = std::numeric_limits<float>::quiet_NaN();
    }
    return replaced;
}

ConstrainedRefinement refineWithConstraints(const HeightGrid& grid,
                                            std::span<const Point2> positions, TinMesh refined,
                                            const BuildOptions& options, ConstraintSources sources,
                                            BuildReport& report, const ProgressCallback& progress) {
    const RefineOptions& refineOptions = *options.refine;
    ConstrainedRefinement result;
    // The constraints have the first half of the phase's progress, the cells the second.
    result.build = addConstraints(std::move(refined), options, report, std::move(sources),
                                  phaseProgress(progress, 0.0, 0.5));
    const unsigned threads = threadsOrAll(
        refineOptions.threads != 0 ? refineOptions.threads : options.triangulation.threads);

    const ConstrainedBuild& build = result.build;
    std::optional<PolygonSet> clip;
    std::optional<PolygonSet> erase;
    std::optional<PolygonSet> replace;
    if (build.clip)
        clip.emplace(*build.clip);
    if (build.erase)
        erase.emplace(*build.erase);
    if (build.replace)
        replace.emplace(*build.replace);
    CellSets cells = cellSets(grid, positions, refineOptions, erase, replace);
    CompletionRules rules;
    rules.measuredCells = std::move(cells.measuredCells);
    rules.openHoleCells = std::move(cells.openHoleCells);
    if (clip || erase)
        rules.outsideArea = [&](const ConstrainedTin& tin) {
            return trianglesOutsideArea(tin, build.openRingEnds, clip ? &*clip : nullptr,
                                        erase ? &*erase : nullptr);
        };
    if (replace)
        rules.unmeasured = [&](const ConstrainedTin& tin) {
            return regionsWhere(tin, build.openRingEnds,
                                [&](Point2 p) { return replace->holds(p); });
        };
    // A cell on a ring is on the shore line.
    rules.afterInsertions = [&result](ConstrainedTin&) { flattenReplaceRings(result.build); };
    result.openHoleCells = cells.allOpenHoleCells;

    Completion completion =
        completeWithCells(grid, positions, result.build.tin, rules, refineOptions, threads,
                          phaseProgress(progress, 0.5, 0.5));
    result.maxError = completion.maxError;
    result.rmse = completion.rmse;
    result.uncoveredCells = completion.uncoveredCells;
    result.holeTriangles = completion.holeTriangles;
    result.passes = completion.passes;
    result.insertedCells = completion.insertedCells;
    result.limitReached = completion.limitReached;
    result.drop = std::move(completion.drop);
    return result;
}

} // namespace terratin::detail

#include "cell_completion.hpp"

#include "completion_check.hpp"
#include "level_schedule.hpp"
#include "stranded_cells.hpp"

#include "terratin/constrain/insert_constraints.hpp"
#include "terratin/error.hpp"

#include <algorithm>
#include <cmath>

namespace terratin::detail {

namespace {

/// The candidates to insert, worst first when a limit cuts them, then in cell order (short
/// walks); empty when a limit leaves no room (`limitReached` set).
std::vector<CellToInsert> chooseCandidates(std::vector<CellToInsert> worst, const TinMesh& mesh,
                                           const RefineOptions& options, bool& limitReached) {
    const std::size_t room =
        std::min(worst.size(), pointsUnderLimits(options.maxPoints, options.maxTriangles,
                                                 mesh.vertexCount(), mesh.triangleCount()));
    if (room < worst.size()) {
        limitReached = true;
        std::sort(worst.begin(), worst.end(), [](const CellToInsert& a, const CellToInsert& b) {
            return a.priority != b.priority ? a.priority > b.priority : a.cell < b.cell;
        });
        worst.resize(room);
    }
    std::sort(worst.begin(), worst.end(),
              [](const CellToInsert& a, const CellToInsert& b) { return a.cell < b.cell; });
    return worst;
}

/// Inserts the candidates' cells into `tin` (insertVertices: constrained edges are never
/// flipped), each walk starting at its candidate's triangle, and marks the triangles that
/// changed in `changed`. Returns how many cells went in.
std::size_t insertCells(const HeightGrid& grid, std::span<const Point2> positions,
                        ConstrainedTin& tin, const std::vector<CellToInsert>& candidates,
                        std::vector<std::uint8_t>& changed, unsigned threads) {
    std::vector<Point3> points;
    std::vector<std::uint32_t> cells; // each point's source index
    std::vector<std::uint32_t> near;  // where each was located: its walk starts there
    for (const CellToInsert& candidate : candidates) {
        const Point2 p = cellPosition(grid, positions, candidate.cell);
        points.push_back({p.x, p.y, double{grid.z[candidate.cell]}});
        cells.push_back(candidate.cell);
        near.push_back(candidate.triangle);
    }
    return insertVertices(tin, points, cells, &changed, near, threads);
}

/// The figures of the last check, a check of every cell, into `result`.
void takeFigures(CompletionMeasure& measure, Completion& result) {
    result.maxError = measure.maxError;
    result.sumSquares = measure.sumSquares;
    result.rmse = measure.covered > 0
                      ? std::sqrt(measure.sumSquares / static_cast<double>(measure.covered))
                      : 0.0;
    result.coveredCells = measure.covered;
    result.uncoveredCells = measure.uncovered;
    result.holeTriangles = measure.holeTriangles;
    result.drop = std::move(measure.drop);
}

} // namespace

Completion completeWithCells(const HeightGrid& grid, std::span<const Point2> positions,
                             ConstrainedTin& tin, const CompletionRules& rules,
                             const RefineOptions& options, unsigned threads,
                             const ProgressCallback& progress) {
    Completion result;
    CompletionCheck check(grid, positions, tin, rules, options.maxError, threads);
    std::vector<std::uint8_t> changed; // empty: every triangle is new to the check
    bool everyCell = false;
    CompletionMeasure measure;
    const auto finalMeasure = [&] {
        return check.measure(changed, true, rules.keepCellErrors ? &result.squaredErrors : nullptr);
    };
    for (;;) {
        if (progress && !progress(1.0 - 1.0 / static_cast<double>(result.passes + 1),
                                  "inserting cells over the bound"))
            throw Cancelled("Constrained refiner: cancelled");
        measure = everyCell ? finalMeasure() : check.measure(changed, false);
        ++result.passes;
        std::vector<CellToInsert> candidates =
            chooseCandidates(std::move(measure.candidates), tin.mesh, options, result.limitReached);
        if (candidates.empty() && everyCell && rules.coverStrandedVertices && !result.limitReached)
            candidates = chooseCandidates(cellsBesideStrandedVertices(grid, tin.mesh, measure.drop,
                                                                      measure.overHoleOnly,
                                                                      rules.insertable),
                                          tin.mesh, options, result.limitReached);
        if (candidates.empty()) {
            if (everyCell)
                break;
            // The changed triangles are within the bound: every cell is measured, for the
            // figures and to make sure.
            everyCell = true;
            changed.assign(tin.mesh.triangleCount(), 0);
            continue;
        }
        everyCell = false;
        const std::size_t inserted =
            insertCells(grid, positions, tin, candidates, changed, threads);
        if (rules.afterInsertions)
            rules.afterInsertions(tin);
        result.insertedCells += inserted;
        if (inserted == 0) {
            measure = finalMeasure();
            break;
        }
    }
    takeFigures(measure, result);
    return result;
}

} // namespace terratin::detail

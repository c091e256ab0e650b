#include "terratin/refine/refine.hpp"

#include "../parallel/round_workers.hpp"
#include "cell_flags.hpp"
#include "error_check.hpp"
#include "greedy_refiner.hpp"
#include "located_check.hpp"

#include "terratin/error.hpp"
#include "terratin/triangulate/mesh_filter.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <string>
#include <thread>
#include <vector>

namespace terratin {

namespace {

using Clock = std::chrono::steady_clock;

double lap(Clock::time_point& start) {
    const Clock::time_point now = Clock::now();
    const double seconds = std::chrono::duration<double>(now - start).count();
    start = now;
    return seconds;
}

void checkInput(const HeightGrid& grid, std::span<const Point2> positions,
                const RefineOptions& options) {
    checkRefineOptions(options);
    checkRefineGrid(grid);
    if (!positions.empty() && positions.size() != grid.cellCount())
        throw InvalidInputError("Refiner: " + std::to_string(positions.size()) + " positions for " +
                                std::to_string(grid.cellCount()) + " cells");
    for (const Point2& p : positions)
        if (!std::isfinite(p.x) || !std::isfinite(p.y))
            throw InvalidInputError("Refiner: a cell position is not finite");
}

} // namespace

void checkRefineGrid(const HeightGrid& grid) {
    if (grid.width <= 0 || grid.height <= 0)
        throw InvalidInputError("Refiner: the grid is empty");
    if (grid.z.size() != grid.cellCount())
        throw InvalidInputError("Refiner: the grid has " + std::to_string(grid.z.size()) +
                                " elevations for " + std::to_string(grid.cellCount()) + " cells");
    if (static_cast<std::uint64_t>(grid.cellCount()) > kMaxRefineCells)
        throw InvalidInputError("Refiner: more than 2^32 - 5 cells; split the raster");
    // NaN marks nodata; an infinite elevation is a value no TIN can carry (the full-resolution
    // path refuses it too, so both paths give the same answer).
    const auto infinite =
        std::find_if(grid.z.begin(), grid.z.end(), [](float z) { return std::isinf(z); });
    if (infinite != grid.z.end()) {
        const auto cell = static_cast<std::size_t>(infinite - grid.z.begin());
        const auto width = static_cast<std::size_t>(grid.width);
        throw InvalidInputError("Refiner: cell " + std::to_string(cell) + " (row " +
                                std::to_string(cell / width) + ", column " +
                                std::to_string(cell % width) + ") has an infinite elevation");
    }
}

namespace {

// The refiner's TIN in cell order into result.mesh, with the refiner's figures; returns the
// triangles to drop over open holes (empty: none, or the caller decides). Holes are decided on
// the whole triangulation; with positions, so are the errors (the walks that locate cells need
// the triangles over holes).
std::vector<std::uint8_t> extractTin(detail::GreedyRefiner& refiner, const detail::GridView& view,
                                     std::span<const Point2> positions,
                                     const RefineOptions& options, unsigned threads,
                                     const ProgressCallback& progress, RefineResult& result) {
    std::vector<detail::TriId> slots;
    result.mesh = refiner.extractInCellOrder(&slots, options.spareVertices);
    std::vector<std::uint8_t> drop;
    if (positions.empty() && !options.keepHoleTriangles)
        drop = refiner.coverStrandedVertices(result.mesh, slots, options.spareVertices, progress);
    else if (result.openHoleCells > 0 && (options.measure || !options.keepHoleTriangles))
        drop = positions.empty()
                   ? detail::trianglesOverOpenHoles(result.mesh, view, threads)
                   : detail::trianglesOverOpenHolesAt(result.mesh, view, positions, threads);
    result.stop = refiner.stop();
    detail::copyRefinerCounts(refiner, result);
    result.completionPasses = refiner.completionPasses();
    return drop;
}

// The guarantee's figures from the errors of the covered valid cells; Error when one is over
// the maximum error the refinement says it reached.
void reportGuarantee(const detail::ErrorMeasure& measure, const detail::CellFlags& flags,
                     const RefineOptions& options, RefineResult& result) {
    result.maxError = measure.maxError;
    result.coveredCells = measure.coveredCells;
    result.rmse = measure.coveredCells > 0
                      ? std::sqrt(measure.sumSquares / static_cast<double>(measure.coveredCells))
                      : 0.0;
    for (const std::uint8_t flag : flags)
        result.validCells += (flag & detail::kCellNoData) == 0 ? 1U : 0U;
    result.uncoveredCells = result.validCells - std::min(result.validCells, result.coveredCells);
    if (options.maxError && result.stop == RefineStop::ErrorReached &&
        result.maxError > *options.maxError)
        throw Error("Refiner: check failed: a covered cell is " + std::to_string(result.maxError) +
                    " from the TIN, more than the maximum error " +
                    std::to_string(*options.maxError));
}

// `result`, the refinement's last progress call made.
RefineResult refined(RefineResult result, const ProgressCallback& progress) {
    if (progress)
        progress(1.0, "refined");
    return result;
}

RefineResult refineAt(const HeightGrid& grid, std::span<const Point2> positions,
                      const RefineOptions& options, const ProgressCallback& progress) {
    checkInput(grid, positions, options);
    RefineResult result;
    Clock::time_point phase = Clock::now();
    const unsigned threads = options.threads != 0
                                 ? options.threads
                                 : std::clamp(std::thread::hardware_concurrency(), 1U, kMaxThreads);
    result.threads = threads;

    detail::CellFlags flags =
        detail::makeCellFlags(grid, options.maxHole, options.fillHoles, result.openHoleCells);
    const detail::GridView view{grid.width, grid.height, grid.z.data(), flags.data()};

    detail::RoundWorkers workers(threads);
    detail::GreedyRefiner refiner(grid, positions, flags, options, workers);
    refiner.run(progress);
    result.insertSeconds = lap(phase);

    std::vector<std::uint8_t> drop =
        extractTin(refiner, view, positions, options, threads, progress, result);
    result.extractSeconds = lap(phase); // with the holes' check and its completion passes

    if (options.validate) {
        detail::checkExactlyDelaunay(result.mesh, "the TIN");
        result.validated = true;
    }
    if (!options.measure) {
        if (!options.keepHoleTriangles && result.openHoleCells > 0)
            result.droppedTriangles = dropTriangles(result.mesh, drop);
        result.extractSeconds += lap(phase);
        return refined(std::move(result), progress);
    }
    if (drop.empty())
        drop.assign(result.mesh.triangleCount(), 0);
    TinMesh whole;
    if (options.keepHoleTriangles && result.openHoleCells > 0) {
        // The whole TIN is kept aside with its arrays' room (a copy has none).
        whole = std::move(result.mesh);
        result.mesh = whole;
    }
    result.extractSeconds += lap(phase);
    detail::ErrorMeasure measure;
    if (!positions.empty())
        measure = detail::measureErrorsAt(result.mesh, drop, view, positions, threads);
    result.checkSeconds = lap(phase);
    if (result.openHoleCells > 0)
        result.droppedTriangles = dropTriangles(result.mesh, drop);
    result.extractSeconds += lap(phase);

    // The guarantee, measured over every valid cell.
    if (positions.empty())
        measure = detail::measureErrors(result.mesh, view, threads);
    reportGuarantee(measure, flags, options, result);
    result.checkSeconds += lap(phase);
    if (options.keepHoleTriangles && result.openHoleCells > 0)
        result.mesh = std::move(whole);
    return refined(std::move(result), progress);
}

} // namespace

void checkRefineOptions(const RefineOptions& options) {
    const auto got = [](std::uint64_t value) { return " (got " + std::to_string(value) + ")"; };
    if (options.maxError && (!std::isfinite(*options.maxError) || *options.maxError < 0.0))
        throw InvalidInputError("Refiner: the maximum error must be finite and >= 0");
    if (options.maxPoints && (*options.maxPoints < 3 || *options.maxPoints > kMaxRefineCells))
        throw InvalidInputError("Refiner: the point limit must be 3 to " +
                                std::to_string(kMaxRefineCells) + got(*options.maxPoints));
    if (options.maxTriangles &&
        (*options.maxTriangles < 1 || *options.maxTriangles > 2 * kMaxRefineCells))
        throw InvalidInputError("Refiner: the triangle limit must be 1 to " +
                                std::to_string(2 * kMaxRefineCells) + got(*options.maxTriangles));
    if (options.maxHole > kMaxRefineCells)
        throw InvalidInputError("Refiner: the largest hole to fill must be 0 to " +
                                std::to_string(kMaxRefineCells) + " cells" + got(options.maxHole));
    if (options.threads > kMaxThreads)
        throw InvalidInputError("Refiner: the thread count must be 0 (all) to " +
                                std::to_string(kMaxThreads) + got(options.threads));
}

const char* toString(RefineStop stop) {
    switch (stop) {
    case RefineStop::ErrorReached:
        return "error";
    case RefineStop::PointLimit:
        return "points";
    case RefineStop::TriangleLimit:
        return "triangles";
    }
    return "unknown";
}

std::vector<std::uint8_t> openHoleCells(const HeightGrid& grid, const RefineOptions& options) {
    std::size_t openCells = 0;
    const detail::CellFlags flags =
        detail::makeCellFlags(grid, options.maxHole, options.fillHoles, openCells);
    std::vector<std::uint8_t> open(flags.size(), 0);
    for (std::size_t cell = 0; cell < flags.size(); ++cell)
        open[cell] = (flags[cell] & detail::kCellOpenHole) != 0 ? 1 : 0;
    return open;
}

RefineResult refine(const HeightGrid& grid, const RefineOptions& options,
                    const ProgressCallback& progress) {
    // A rotated geotransform (GT[2] or GT[4] != 0) rounds the centres of a row off their
    // common line by an ulp or so. The pixel-space scans then disagree with the TIN, which is
    // built at the rounded centres, about the cells on its border: the hull's corners include
    // border cells the rounding pushed out, and a cell on a pixel-space edge may lie in the
    // sliver beside it (the triangulator then finds "a point outside the hull", and cells are
    // left unchecked).
    // The path for reprojected grids locates every cell exactly at its position, so the
    // rotated grid takes it with the centres as positions (16 bytes per cell).
    const std::array<double, 6>& c = grid.geoTransform;
    if ((c[2] != 0.0 || c[4] != 0.0) && grid.width > 0 && grid.height > 0 &&
        static_cast<std::uint64_t>(grid.cellCount()) <= kMaxRefineCells) {
        checkRefineOptions(options);
        std::vector<Point2> centres(grid.cellCount());
        for (std::size_t cell = 0; cell < centres.size(); ++cell)
            centres[cell] = grid.cellCentre(static_cast<std::uint64_t>(cell));
        return refineAt(grid, centres, options, progress);
    }
    return refineAt(grid, {}, options, progress);
}

RefineResult refine(const HeightGrid& grid, std::span<const Point2> positions,
                    const RefineOptions& options, const ProgressCallback& progress) {
    if (positions.empty())
        throw InvalidInputError("Refiner: no cell positions given");
    return refineAt(grid, positions, options, progress);
}

} // namespace terratin

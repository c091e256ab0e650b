#include "tile_refine.hpp"

#include "border_profile.hpp"
#include "tile_grid.hpp"
#include "tile_mesh_merge.hpp"
#include "tile_refinement.hpp"

#include "../refine/cell_flags.hpp"
#include "../refine/error_check.hpp"
#include "../refine/greedy_refiner.hpp"
#include "../refine/round_workers.hpp"

#include "terratin/error.hpp"
#include "terratin/refine/mesh_filter.hpp"
#include "terratin/refine/tile_distribution.hpp"
#include "terratin/triangulate/mesh_validation.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <string>
#include <thread>
#include <vector>

namespace terratin::detail {

namespace {

struct TileWindow {
    CellRange rows;
    CellRange columns;
};

/// The window's cells of a row-major array of `gridWidth` columns, row-major in the window.
template <class Array>
Array windowCells(const Array& cells, std::size_t gridWidth, const TileWindow& window) {
    Array copy(window.rows.count() * window.columns.count());
    for (std::size_t row = 0; row < window.rows.count(); ++row) {
        const auto from =
            cells.begin() + static_cast<std::ptrdiff_t>((window.rows.first + row) * gridWidth +
                                                        window.columns.first);
        std::copy(from, from + static_cast<std::ptrdiff_t>(window.columns.count()),
                  copy.begin() + static_cast<std::ptrdiff_t>(row * window.columns.count()));
    }
    return copy;
}

HeightGrid windowOf(const HeightGrid& grid, const TileWindow& window) {
    HeightGrid tile;
    tile.width = static_cast<int>(window.columns.count());
    tile.height = static_cast<int>(window.rows.count());
    tile.geoTransform = grid.geoTransform;
    tile.firstRow = grid.firstRow + static_cast<int>(window.rows.first);
    tile.firstColumn = grid.firstColumn + static_cast<int>(window.columns.first);
    tile.z = windowCells(grid.z, static_cast<std::size_t>(grid.width), window);
    return tile;
}

/// Whether the valid cells of `grid` span an area (three of them not on one line), which the
/// refiner needs. Exact: pixel coordinates are integers.
bool validCellsSpanArea(const HeightGrid& grid) {
    const auto width = static_cast<std::int64_t>(grid.width);
    std::int64_t first = -1;
    std::int64_t second = -1;
    for (std::int64_t cell = 0; cell < static_cast<std::int64_t>(grid.cellCount()); ++cell) {
        if (!grid.isValid(static_cast<std::size_t>(cell)))
            continue;
        if (first < 0) {
            first = cell;
        } else if (second < 0) {
            second = cell;
        } else {
            const std::int64_t ac = cell % width - first % width;
            const std::int64_t ar = cell / width - first / width;
            const std::int64_t bc = second % width - first % width;
            const std::int64_t br = second / width - first / width;
            if (bc * ar != br * ac)
                return true;
        }
    }
    return false;
}

/// The cells of one side of a tile, in the grid and in the tile (row-major indices).
struct Side {
    std::vector<std::size_t> gridCells;
    std::vector<std::uint32_t> tileCells;
};

/// The four sides, each in increasing row or column order as keptBorderCells reads them (the
/// same order from either tile): top, right, bottom, left.
std::vector<Side> sidesOf(std::size_t gridWidth, const TileWindow& window) {
    const std::size_t width = window.columns.count();
    const std::size_t height = window.rows.count();
    const auto cell = [&](std::size_t row, std::size_t column) {
        return std::pair{(window.rows.first + row) * gridWidth + window.columns.first + column,
                         static_cast<std::uint32_t>(row * width + column)};
    };
    std::vector<Side> sides(4);
    for (std::size_t column = 0; column < width; ++column)
        for (const auto& [side, row] : {std::pair{0, std::size_t{0}}, {2, height - 1}}) {
            const auto [gridCell, tileCell] = cell(row, column);
            sides[static_cast<std::size_t>(side)].gridCells.push_back(gridCell);
            sides[static_cast<std::size_t>(side)].tileCells.push_back(tileCell);
        }
    for (std::size_t row = 0; row < height; ++row)
        for (const auto& [side, column] : {std::pair{1, width - 1}, {3, std::size_t{0}}}) {
            const auto [gridCell, tileCell] = cell(row, column);
            sides[static_cast<std::size_t>(side)].gridCells.push_back(gridCell);
            sides[static_cast<std::size_t>(side)].tileCells.push_back(tileCell);
        }
    return sides;
}

/// Freezes every cell on the tile's sides in `flags` and returns the cells the sides keep
/// (the refiner's seeds), side after side.
std::vector<std::uint32_t> seedTheSides(const HeightGrid& grid, const TileWindow& window,
                                        double tolerance, CellFlags& flags) {
    std::vector<std::uint32_t> seeds;
    std::vector<float> elevations;
    for (const Side& side : sidesOf(static_cast<std::size_t>(grid.width), window)) {
        elevations.clear();
        for (const std::size_t cell : side.gridCells)
            elevations.push_back(grid.z[cell]);
        for (const std::uint32_t k : keptBorderCells(elevations, tolerance))
            seeds.push_back(side.tileCells[k]);
        for (const std::uint32_t cell : side.tileCells)
            flags[cell] |= kCellFrozen;
    }
    return seeds;
}

} // namespace

double sideTolerance(const HeightGrid& grid, double maxError) {
    double largest = 0.0;
    for (const float z : grid.z)
        if (!std::isnan(z))
            largest = std::max(largest, std::abs(double{z}));
    return std::max(0.0, maxError - 1e-9 * (largest + maxError + 1.0));
}

namespace {

/// Drops the tile's triangles over open holes and measures its largest error over every valid
/// cell, the sides' included, in the pixel coordinates the tile's scans used.
void dropHolesAndMeasure(const HeightGrid& tileGrid, CellFlags& tileFlags, unsigned threads,
                         TileRefinement& tile) {
    for (std::uint8_t& flag : tileFlags)
        flag &= static_cast<std::uint8_t>(~kCellFrozen);
    const GridView view{tileGrid.width, tileGrid.height, tileGrid.z.data(), tileFlags.data()};
    const bool anyOpenHole = std::any_of(tileFlags.begin(), tileFlags.end(),
                                         [](std::uint8_t f) { return (f & kCellOpenHole) != 0; });
    if (anyOpenHole)
        tile.droppedTriangles =
            dropTriangles(tile.mesh, trianglesOverOpenHoles(tile.mesh, view, threads));
    tile.maxError = measureErrors(tile.mesh, view, threads).maxError;
}

TileRefinement refineTile(const HeightGrid& grid, const CellFlags& flags, const TileWindow& window,
                          double tolerance, const RefineOptions& options, RoundWorkers& workers,
                          const ProgressCallback& progress) {
    TileRefinement tile;
    const HeightGrid tileGrid = windowOf(grid, window);
    if (!validCellsSpanArea(tileGrid))
        return tile;
    CellFlags tileFlags = windowCells(flags, static_cast<std::size_t>(grid.width), window);
    std::vector<std::uint32_t> seeds = seedTheSides(grid, window, tolerance, tileFlags);

    GreedyRefiner refiner(tileGrid, {}, tileFlags, options, workers);
    refiner.setSeedCells(std::move(seeds));
    refiner.run(progress);
    tile.hullPoints = refiner.hullPoints();
    tile.strips = refiner.strips();
    tile.levels = refiner.levels();
    tile.deferredCandidates = refiner.deferred();
    tile.pairInsertions = refiner.pairInsertions();
    tile.sharedInsertions = refiner.sharedInsertions();
    tile.meshBytes = refiner.meshBytes();
    tile.mesh = refiner.extractInCellOrder();
    if (options.validate) {
        const MeshValidation validation = validateDelaunay(tile.mesh);
        if (!validation.ok())
            throw Error("Refiner: a tile's TIN is not an exact Delaunay triangulation: " +
                        (validation.problems.empty() ? std::string("unknown problem")
                                                     : validation.problems.front()));
    }

    dropHolesAndMeasure(tileGrid, tileFlags, workers.size(), tile);
    return tile;
}

void addFigures(const TileRefinement& tile, RefineResult& result) {
    result.maxError = std::max(result.maxError, tile.maxError);
    result.droppedTriangles += tile.droppedTriangles;
    result.hullPoints += tile.hullPoints;
    result.strips = std::max(result.strips, tile.strips);
    result.levels = std::max(result.levels, tile.levels);
    result.deferredCandidates += tile.deferredCandidates;
    result.pairInsertions += tile.pairInsertions;
    result.sharedInsertions += tile.sharedInsertions;
    result.meshBytes = std::max(result.meshBytes, tile.meshBytes);
}

/// rmse and the covered cells, over the joined TIN (each cell once).
void measureJoined(const HeightGrid& grid, CellFlags flags, RefineResult& result) {
    for (const std::uint8_t flag : flags)
        result.validCells += (flag & kCellNoData) == 0 ? 1U : 0U;
    for (const std::uint32_t cell : result.mesh.sourceIndex)
        flags[cell] |= kCellVertex;
    const GridView view{grid.width, grid.height, grid.z.data(), flags.data()};
    const ErrorMeasure measure = measureErrors(result.mesh, view, result.threads);
    result.coveredCells = measure.coveredCells;
    result.rmse = measure.coveredCells > 0
                      ? std::sqrt(measure.sumSquares / static_cast<double>(measure.coveredCells))
                      : 0.0;
    result.uncoveredCells = result.validCells - std::min(result.validCells, result.coveredCells);
}

/// What every tile needs, decided once for the whole grid.
struct TileJob {
    const HeightGrid* grid;
    CellFlags flags;
    double tolerance;
    TileGrid tiles;
    RefineOptions options;

    [[nodiscard]] TileWindow window(std::size_t tile) const {
        return {tiles.rowsOf(tile / tiles.tileColumns()),
                tiles.columnsOf(tile % tiles.tileColumns())};
    }
};

/// Joins tiles in tile order, whatever order they are refined in.
class TileJoin {
public:
    TileJoin(const TileJob& job, RefineResult& result)
        : m_job(&job), m_result(&result), m_merger(static_cast<std::size_t>(job.grid->width)) {}

    void take(std::size_t tile, TileRefinement refinement) {
        m_waiting.emplace(tile, std::move(refinement));
        for (auto next = m_waiting.find(m_joined); next != m_waiting.end();
             next = m_waiting.find(m_joined)) {
            const TileWindow window = m_job->window(m_joined);
            if (next->second.mesh.triangleCount() > 0)
                m_merger.add(next->second.mesh, {window.rows.first, window.columns.first,
                                                 window.columns.count(), window.rows.count()});
            addFigures(next->second, *m_result);
            m_waiting.erase(next);
            ++m_joined;
        }
    }
    [[nodiscard]] std::size_t joined() const { return m_joined; }
    [[nodiscard]] TinMesh finish() { return m_merger.finish(); }

private:
    const TileJob* m_job;
    RefineResult* m_result;
    TileMeshMerger m_merger;
    std::map<std::size_t, TileRefinement> m_waiting;
    std::size_t m_joined = 0;
};

/// Every tile refined here, one after the other, each on all the threads.
void refineEveryTile(const TileJob& job, RoundWorkers& workers, TileJoin& join,
                     const ProgressCallback& progress) {
    const std::size_t count = job.tiles.tileCount();
    for (std::size_t tile = 0; tile < count; ++tile) {
        ProgressCallback tileProgress;
        if (progress)
            tileProgress = [&progress, tile, count](double fraction, std::string_view message) {
                return progress(0.9 * (static_cast<double>(tile) + fraction) /
                                    static_cast<double>(count),
                                message);
            };
        join.take(tile, refineTile(*job.grid, job.flags, job.window(tile), job.tolerance,
                                   job.options, workers, tileProgress));
    }
}

/// The tiles refined by the other processes of `distribution`, joined here.
void gatherEveryTile(const TileJob& job, TileDistribution& distribution, TileJoin& join,
                     const ProgressCallback& progress) {
    const std::size_t count = job.tiles.tileCount();
    distribution.gather(
        count,
        [&join](std::size_t tile, std::vector<std::byte> bytes) {
            join.take(tile, unpackTile(bytes));
        },
        [&] {
            return !progress ||
                   progress(0.9 * static_cast<double>(join.joined()) / static_cast<double>(count),
                            "refining tiles");
        });
}

} // namespace

RefineResult refineInTiles(const HeightGrid& grid, const RefineOptions& options,
                           const ProgressCallback& progress) {
    using Clock = std::chrono::steady_clock;
    const Clock::time_point start = Clock::now();
    RefineResult result;
    result.threads = options.threads != 0
                         ? options.threads
                         : std::clamp(std::thread::hardware_concurrency(), 1U, kMaxThreads);
    TileJob job{&grid,
                makeCellFlags(grid, options.maxHole, options.fillHoles, result.openHoleCells),
                sideTolerance(grid, *options.maxError),
                TileGrid(static_cast<std::size_t>(grid.width),
                         static_cast<std::size_t>(grid.height), options.tileSize),
                options};
    job.options.tileSize = 0;
    job.options.threads = result.threads;
    job.options.distribution = nullptr;
    RoundWorkers workers(result.threads);
    TileDistribution* const distribution = options.distribution;
    if (distribution != nullptr && !distribution->coordinates()) {
        distribution->serve([&](std::size_t tile) {
            return packTile(refineTile(grid, job.flags, job.window(tile), job.tolerance,
                                       job.options, workers, progress));
        });
        return result; // the coordinator has the TIN
    }
    TileJoin join(job, result);
    if (distribution != nullptr)
        gatherEveryTile(job, *distribution, join, progress);
    else
        refineEveryTile(job, workers, join, progress);
    result.validated = options.validate;
    result.insertSeconds = std::chrono::duration<double>(Clock::now() - start).count();
    result.mesh = join.finish();
    if (result.maxError > *options.maxError)
        throw Error("Refiner: check failed: a covered cell is " + std::to_string(result.maxError) +
                    " from the TIN, more than the maximum error " +
                    std::to_string(*options.maxError));
    measureJoined(grid, job.flags, result);
    result.checkSeconds =
        std::chrono::duration<double>(Clock::now() - start).count() - result.insertSeconds;
    if (progress)
        progress(1.0, "refined");
    return result;
}

} // namespace terratin::detail

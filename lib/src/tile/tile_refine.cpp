#include "tile_refine.hpp"

#include "one_tile.hpp"
#include "pixel_frame.hpp"
#include "projected_tile.hpp"
#include "tile_grid.hpp"
#include "tile_mesh_merge.hpp"
#include "tile_refinement.hpp"

#include "../parallel/round_workers.hpp"

#include "terratin/error.hpp"
#include "terratin/tile/tile_distribution.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <map>
#include <optional>
#include <string>
#include <thread>
#include <vector>

namespace terratin::detail {

namespace {

void addFigures(const TileRefinement& tile, RefineResult& result) {
    result.maxError = std::max(result.maxError, tile.maxError);
    if (result.stop == RefineStop::ErrorReached)
        result.stop = tile.stop; // a tile stopped by its share of a limit
    result.validCells += tile.validCells;
    result.openHoleCells += tile.openHoleCells;
    result.coveredCells += tile.coveredCells;
    result.droppedTriangles += tile.droppedTriangles;
    result.hullPoints += tile.hullPoints;
    result.strips = std::max(result.strips, tile.strips);
    result.levels = std::max(result.levels, tile.levels);
    result.deferredCandidates += tile.deferredCandidates;
    result.pairInsertions += tile.pairInsertions;
    result.sharedInsertions += tile.sharedInsertions;
    result.meshBytes += tile.meshBytes;
}

/// What every tile needs.
struct TileJob {
    CellSource* cells;
    TileGrid tiles;
    TiledRefineOptions options;
    /// Each tile's share of options.maxPoints and maxTriangles (empty without them).
    std::vector<std::size_t> pointShares;
    std::vector<std::size_t> triangleShares;
    /// A rotated grid's geotransform, its tiles refined in the pixel frame (pixel_frame.hpp).
    std::optional<std::array<double, 6>> world;

    [[nodiscard]] TilePlace place(std::size_t tile) const { return tiles.placeOf(tile); }
    [[nodiscard]] TiledRefineOptions optionsOf(std::size_t tile) const {
        TiledRefineOptions tileOptions = options;
        if (!pointShares.empty())
            tileOptions.maxPoints = pointShares[tile];
        if (!triangleShares.empty())
            tileOptions.maxTriangles = triangleShares[tile];
        return tileOptions;
    }
};

/// What a limit's shares need to know of a tile, from its cells alone.
struct TileTally {
    /// Valid cells the tile owns (its top and left sides, its bottom and right ones only on
    /// the grid's edge: each cell of the grid once).
    std::uint64_t ownedCells = 0;
    /// The vertices its sides keep within the maximum error, and those of them it owns.
    std::uint64_t sideVertices = 0;
    std::uint64_t ownedSideVertices = 0;
};

/// Every tile's tally, reading a tile's window at a time.
std::vector<TileTally> tallyTiles(CellSource& cells, const TileGrid& tiles,
                                  const TiledRefineOptions& options) {
    std::vector<TileTally> tallies(tiles.tileCount());
    for (std::size_t tile = 0; tile < tallies.size(); ++tile) {
        const TilePlace place = tiles.placeOf(tile);
        const HeightGrid window =
            cells.window(static_cast<int>(place.firstRow), static_cast<int>(place.height),
                         static_cast<int>(place.firstColumn), static_cast<int>(place.width));
        const UnownedSides unowned = tiles.unownedSidesOf(tile);
        const auto owned = [&](std::size_t cell) {
            return !unowned(cell, place.width, place.height);
        };
        TileTally& tally = tallies[tile];
        for (std::size_t cell = 0; cell < window.cellCount(); ++cell)
            tally.ownedCells += window.isValid(cell) && owned(cell) ? 1U : 0U;
        std::vector<std::uint32_t> kept;
        if (options.cellPositions) {
            kept = keptProjectedSideCells(cells, tiles, tile, options);
        } else {
            kept = keptSideCells(window, *options.maxError);
            std::sort(kept.begin(), kept.end());
            kept.erase(std::unique(kept.begin(), kept.end()), kept.end());
        }
        tally.sideVertices = kept.size();
        for (const std::uint32_t cell : kept)
            tally.ownedSideVertices += owned(cell) ? 1U : 0U;
    }
    return tallies;
}

/// floor(spare * part / whole), exactly in 64 bits (a grid has fewer than 2^32 cells).
std::uint64_t shareOf(std::uint64_t spare, std::uint64_t part, std::uint64_t whole) {
    return whole == 0 ? 0 : spare / whole * part + spare % whole * part / whole;
}

[[noreturn]] void refuseLimit(const std::string& what, std::uint64_t needed, std::uint64_t limit) {
    throw InvalidInputError("Refiner: the tiles' sides alone take " + std::to_string(needed) + " " +
                            what + " within the maximum error, more than the limit of " +
                            std::to_string(limit) +
                            "; raise the limit or the maximum error, or make the tiles larger");
}

/// The tiles' shares of a point or triangle limit, when there is one. Points: each tile keeps
/// its sides' vertices, and what the sides leave of the limit goes to the tiles in proportion to
/// the valid cells they own; the vertices each tile owns then add up to the limit at most.
/// Triangles: a tile's sides' vertices alone make that many less 2 triangles; what those leave
/// is shared the same way, and every triangle is one tile's.
void shareTheLimits(TileJob& job) {
    if (!job.options.maxPoints && !job.options.maxTriangles)
        return;
    const std::vector<TileTally> tallies = tallyTiles(*job.cells, job.tiles, job.options);
    std::uint64_t cells = 0;
    std::uint64_t sidePoints = 0;
    std::uint64_t sideTriangles = 0;
    for (const TileTally& tally : tallies) {
        cells += tally.ownedCells;
        sidePoints += tally.ownedSideVertices;
        sideTriangles += std::max<std::uint64_t>(tally.sideVertices, 2) - 2;
    }
    if (const std::optional<std::size_t> limit = job.options.maxPoints) {
        if (sidePoints > *limit)
            refuseLimit("points", sidePoints, *limit);
        for (const TileTally& tally : tallies)
            job.pointShares.push_back(tally.sideVertices +
                                      shareOf(*limit - sidePoints, tally.ownedCells, cells));
    }
    if (const std::optional<std::size_t> limit = job.options.maxTriangles) {
        if (sideTriangles > *limit)
            refuseLimit("triangles", sideTriangles, *limit);
        for (const TileTally& tally : tallies)
            job.triangleShares.push_back(std::max<std::uint64_t>(tally.sideVertices, 2) - 2 +
                                         shareOf(*limit - sideTriangles, tally.ownedCells, cells));
    }
}

/// Joins tiles in tile order, whatever order they are refined in.
class TileJoin {
public:
    TileJoin(const TileJob& job, RefineResult& result)
        : m_job(&job), m_result(&result), m_merger(static_cast<std::size_t>(job.cells->width())) {}

    void take(std::size_t tile, TileRefinement refinement) {
        m_waiting.emplace(tile, std::move(refinement));
        for (auto next = m_waiting.find(m_joined); next != m_waiting.end();
             next = m_waiting.find(m_joined)) {
            // The guarantee, checked before the tile goes anywhere.
            const double bound = m_job->options.maxError.value_or(0.0); // every cell: 0
            if (next->second.stop == RefineStop::ErrorReached && next->second.maxError > bound)
                throw Error("Refiner: check failed: a covered cell of tile " +
                            std::to_string(m_joined) + " is " +
                            std::to_string(next->second.maxError) +
                            " from the TIN, more than the maximum error " + std::to_string(bound));
            countSideCells(next->second, m_job->place(m_joined));
            if (next->second.mesh.triangleCount() > 0)
                pass(next->second.mesh, m_job->place(m_joined));
            addFigures(next->second, *m_result);
            m_sumSquares += next->second.sumSquares;
            m_waiting.erase(next);
            ++m_joined;
        }
    }
    [[nodiscard]] std::size_t joined() const { return m_joined; }
    [[nodiscard]] double sumSquares() const { return m_sumSquares; }
    [[nodiscard]] TinMesh finish() { return m_merger.finish(); }

private:
    /// A side cell its owner (this tile) leaves uncovered is covered when an earlier tile
    /// covered it; an earlier tile's cover is kept until the cell's owner is joined.
    void countSideCells(const TileRefinement& tile, const TilePlace& place) {
        const auto gridWidth = static_cast<std::size_t>(m_job->cells->width());
        const auto gridCell = [&](std::uint32_t cell) {
            return (place.firstRow + cell / place.width) * gridWidth + place.firstColumn +
                   cell % place.width;
        };
        for (const std::uint32_t cell : tile.uncoveredSharedSides) {
            const auto earlier = m_laterCover.find({m_joined, gridCell(cell)});
            if (earlier == m_laterCover.end())
                continue;
            ++m_result->coveredCells;
            m_sumSquares += earlier->second;
        }
        m_laterCover.erase(m_laterCover.begin(), m_laterCover.lower_bound({m_joined + 1, 0}));
        for (const SideCell& side : tile.coveredForLaterTiles) {
            const std::size_t cell = gridCell(side.cell);
            const std::size_t owner = m_job->tiles.ownerOf(cell / gridWidth, cell % gridWidth);
            m_laterCover.emplace(std::pair{owner, cell}, side.squaredError);
        }
    }

    /// To the caller's sink, numbered by the grid's cells, or into the joined TIN.
    void pass(TinMesh& tile, const TilePlace& place) {
        if (m_job->world)
            mapTileToWorld(tile, place, *m_job->world);
        if (!m_job->options.tileSink) {
            m_merger.add(tile, place);
            return;
        }
        const auto gridWidth = static_cast<std::size_t>(m_job->cells->width());
        for (std::uint32_t& cell : tile.sourceIndex)
            cell = static_cast<std::uint32_t>((place.firstRow + cell / place.width) * gridWidth +
                                              place.firstColumn + cell % place.width);
        m_job->options.tileSink(m_joined, std::move(tile));
    }

    const TileJob* m_job;
    RefineResult* m_result;
    TileMeshMerger m_merger;
    std::map<std::size_t, TileRefinement> m_waiting;
    /// Side cells covered by a tile joined already, keyed by their owner and the grid's cell
    /// index: their squared errors.
    std::map<std::pair<std::size_t, std::size_t>, double> m_laterCover;
    std::size_t m_joined = 0;
    double m_sumSquares = 0.0;
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
        join.take(tile, refineOneTile(*job.cells, job.tiles, tile, job.optionsOf(tile), workers,
                                      tileProgress));
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
        },
        job.options.earlyTileBytes);
}

} // namespace

RefineResult refineInTiles(CellSource& cells, const TiledRefineOptions& options,
                           const ProgressCallback& progress) {
    using Clock = std::chrono::steady_clock;
    const Clock::time_point start = Clock::now();
    RefineResult result;
    result.threads = options.threads != 0
                         ? options.threads
                         : std::clamp(std::thread::hardware_concurrency(), 1U, kMaxThreads);
    std::optional<PixelFrameCells> frame;
    if (isRotated(cells.geoTransform()) && !options.cellPositions)
        frame.emplace(cells); // positions place the cells themselves
    TileJob job{frame ? &*frame : &cells,
                TileGrid(static_cast<std::size_t>(cells.width()),
                         static_cast<std::size_t>(cells.height()), options.tileSize),
                options,
                {},
                {},
                {}};
    if (frame)
        job.world = cells.geoTransform();
    job.options.tileSize = 0;
    job.options.threads = result.threads;
    job.options.distribution = nullptr;

    RoundWorkers workers(result.threads);
    TileDistribution* const distribution = options.distribution;
    if (distribution == nullptr || !distribution->coordinates())
        shareTheLimits(job); // where tiles are refined
    if (distribution != nullptr && !distribution->coordinates()) {
        distribution->serve([&](std::size_t tile) {
            return packTile(
                refineOneTile(*job.cells, job.tiles, tile, job.optionsOf(tile), workers, progress));
        });
        return result; // the coordinator has the TIN
    }
    TileJoin join(job, result);
    if (distribution != nullptr)
        gatherEveryTile(job, *distribution, join, progress);
    else
        refineEveryTile(job, workers, join, progress);
    result.validated = options.validate;
    result.mesh = join.finish();
    result.insertSeconds = std::chrono::duration<double>(Clock::now() - start).count();
    if (result.validCells == 0)
        throw InvalidInputError("Refiner: the grid has no valid cell");
    result.rmse = result.coveredCells > 0
                      ? std::sqrt(join.sumSquares() / static_cast<double>(result.coveredCells))
                      : 0.0;
    result.uncoveredCells = result.validCells - std::min(result.validCells, result.coveredCells);
    if (progress)
        progress(1.0, "refined");
    return result;
}

} // namespace terratin::detail

#include "one_tile.hpp"

#include "border_profile.hpp"
#include "projected_tile.hpp"
#include "tile_cells.hpp"

#include "../parallel/round_workers.hpp"
#include "../refine/cell_flags.hpp"
#include "../refine/error_check.hpp"
#include "../refine/error_measure.hpp"
#include "../refine/greedy_refiner.hpp"

#include "terratin/error.hpp"
#include "terratin/triangulate/mesh_filter.hpp"
#include "terratin/triangulate/triangulate.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <span>
#include <string>
#include <vector>

namespace terratin::detail {

namespace {

/// Freezes every cell on the tile's sides in `flags` and returns the cells the sides keep
/// (the refiner's seeds), side after side.
std::vector<std::uint32_t> seedTheSides(const HeightGrid& tile, double maxError, CellFlags& flags) {
    for (const std::vector<std::uint32_t>& side :
         sidesOf(static_cast<std::size_t>(tile.width), static_cast<std::size_t>(tile.height)))
        for (const std::uint32_t cell : side)
            flags[cell] |= kCellFrozen;
    return keptSideCells(tile, maxError);
}

/// For each triangle of `mesh`, 1 when it covers a cell of an open hole; empty when the tile
/// has none.
std::vector<std::uint8_t> trianglesOverHoles(const HeightGrid& grid, const CellFlags& flags,
                                             const TinMesh& mesh, unsigned threads) {
    if (std::none_of(flags.begin(), flags.end(),
                     [](std::uint8_t f) { return (f & kCellOpenHole) != 0; }))
        return {};
    const GridView view{grid.width, grid.height, grid.z.data(), flags.data()};
    return trianglesOverOpenHoles(mesh, view, threads);
}

/// Drops the tile's triangles marked in `drop` (over open holes; empty: none), clearing the sides'
/// kCellFrozen first.
void dropHoles(CellFlags& flags, std::span<const std::uint8_t> drop, TileRefinement& tile) {
    for (std::uint8_t& flag : flags)
        flag &= static_cast<std::uint8_t>(~kCellFrozen);
    if (!drop.empty())
        tile.droppedTriangles = dropTriangles(tile.mesh, drop);
}

/// Measures the tile's largest error over every valid cell, the sides' included, in the pixel
/// coordinates its scans used; and the covered cells it owns with their squared errors.
void measure(const HeightGrid& grid, CellFlags& flags, UnownedSides unowned, unsigned threads,
             TileRefinement& tile) {
    const GridView view{grid.width, grid.height, grid.z.data(), flags.data()};
    tile.maxError = measureErrors(tile.mesh, view, threads).maxError;

    const auto width = static_cast<std::size_t>(grid.width);
    const auto height = static_cast<std::size_t>(grid.height);
    std::size_t unownedVertices = 0;
    for (const std::uint32_t cell : tile.mesh.sourceIndex)
        unownedVertices += unowned(cell, width, height) ? 1U : 0U;
    for (std::size_t cell = 0; cell < flags.size(); ++cell)
        if (unowned(cell, width, height))
            flags[cell] |= kCellFrozen; // not counted here: the neighbour owns them
    const ErrorMeasure owned = measureErrors(tile.mesh, view, threads);
    tile.coveredCells = owned.coveredCells - unownedVertices;
    tile.sumSquares = owned.sumSquares;
}

/// The tile's four sides, each a line of cells: its errors, NaN where the tile covers no cell.
class SideCover {
public:
    explicit SideCover(const HeightGrid& grid)
        : m_width(static_cast<std::size_t>(grid.width)),
          m_height(static_cast<std::size_t>(grid.height)),
          m_rows{std::vector<double>(m_width, kNone), std::vector<double>(m_width, kNone)},
          m_columns{std::vector<double>(m_height, kNone), std::vector<double>(m_height, kNone)} {}

    /// Cell (row, col) has squared error `squared` in a kept triangle, if it is on a side.
    void cover(std::size_t row, std::size_t col, double squared) {
        if (row == 0 || row == m_height - 1)
            m_rows[row == 0 ? 0 : 1][col] = squared;
        if (col == 0 || col == m_width - 1)
            m_columns[col == 0 ? 0 : 1][row] = squared;
    }
    /// The squared error of side cell (row, col), NaN when uncovered.
    [[nodiscard]] double at(std::size_t row, std::size_t col) const {
        if (row == 0 || row == m_height - 1)
            return m_rows[row == 0 ? 0 : 1][col];
        return m_columns[col == 0 ? 0 : 1][row];
    }

private:
    static constexpr double kNone = std::numeric_limits<double>::quiet_NaN();
    std::size_t m_width;
    std::size_t m_height;
    std::array<std::vector<double>, 2> m_rows;    // top, bottom
    std::array<std::vector<double>, 2> m_columns; // left, right
};

/// How the tile's TIN covers its sides. A side is the tile's hull there, so a side cell is
/// covered by a kept triangle's vertex or edge along the side (its error along that edge), by
/// no other.
SideCover coverOfSides(const HeightGrid& grid, const TinMesh& mesh) {
    const auto width = static_cast<std::size_t>(grid.width);
    const auto height = static_cast<std::size_t>(grid.height);
    SideCover sides(grid);
    const auto rowOf = [&](std::uint32_t v) { return mesh.sourceIndex[v] / width; };
    const auto colOf = [&](std::uint32_t v) { return mesh.sourceIndex[v] % width; };
    // The sides each vertex lies on (bits: top, bottom, left, right), found once.
    std::vector<std::uint8_t> onSides(mesh.vertexCount(), 0);
    for (std::uint32_t v = 0; v < onSides.size(); ++v)
        onSides[v] = static_cast<std::uint8_t>(
            (rowOf(v) == 0 ? 1U : 0U) | (rowOf(v) == height - 1 ? 2U : 0U) |
            (colOf(v) == 0 ? 4U : 0U) | (colOf(v) == width - 1 ? 8U : 0U));
    for (std::size_t t = 0; t < mesh.triangleCount(); ++t)
        for (std::size_t e = 0; e < 3; ++e) {
            const std::uint32_t a = mesh.triangles[3 * t + e];
            const std::uint32_t b = mesh.triangles[3 * t + (e + 1) % 3];
            const unsigned common = onSides[a] & onSides[b];
            if (onSides[a] != 0)
                sides.cover(rowOf(a), colOf(a), 0.0);
            if (common == 0)
                continue;
            const bool alongRow = (common & 3U) != 0;
            const std::size_t from = alongRow ? colOf(a) : rowOf(a);
            const std::size_t to = alongRow ? colOf(b) : rowOf(b);
            const double za = mesh.vertices[a].z;
            const double zb = mesh.vertices[b].z;
            for (std::size_t k = std::min(from, to) + 1; k < std::max(from, to); ++k) {
                const std::size_t row = alongRow ? rowOf(a) : k;
                const std::size_t col = alongRow ? k : colOf(a);
                const double z = grid.z[row * width + col];
                if (std::isnan(z))
                    continue;
                const double along = (static_cast<double>(k) - static_cast<double>(from)) /
                                     (static_cast<double>(to) - static_cast<double>(from));
                const double error = cellError(z, za + (zb - za) * along);
                sides.cover(row, col, error * error);
            }
        }
    return sides;
}

/// Fills the tile's coveredForLaterTiles and uncoveredSharedSides from its final TIN.
void coverTheSides(const HeightGrid& grid, bool topShared, bool leftShared, UnownedSides unowned,
                   TileRefinement& tile) {
    const auto width = static_cast<std::size_t>(grid.width);
    const auto height = static_cast<std::size_t>(grid.height);
    const SideCover sides = coverOfSides(grid, tile.mesh);
    const auto report = [&](std::size_t row, std::size_t col) {
        const std::size_t cell = row * width + col;
        const bool shared = (topShared && row == 0) || (leftShared && col == 0);
        const bool later = unowned(cell, width, height);
        if ((!shared && !later) || std::isnan(grid.z[cell]))
            return;
        const double squared = sides.at(row, col);
        if (later && !std::isnan(squared))
            tile.coveredForLaterTiles.push_back({static_cast<std::uint32_t>(cell), squared});
        else if (!later && std::isnan(squared))
            tile.uncoveredSharedSides.push_back(static_cast<std::uint32_t>(cell));
    };
    for (std::size_t col = 0; col < width; ++col) {
        report(0, col);
        if (height > 1)
            report(height - 1, col);
    }
    for (std::size_t row = 1; row + 1 < height; ++row) {
        report(row, 0);
        if (width > 1)
            report(row, width - 1);
    }
}

/// The measure of a tile whose every valid cell is a vertex: no error anywhere; a cell it owns
/// is covered while a triangle keeps its vertex (the measure's rule for vertex cells).
void measureEveryCell(const HeightGrid& grid, UnownedSides unowned, TileRefinement& tile) {
    const auto width = static_cast<std::size_t>(grid.width);
    const auto height = static_cast<std::size_t>(grid.height);
    std::vector<std::uint8_t> used(tile.mesh.vertexCount(), 0);
    for (const std::uint32_t v : tile.mesh.triangles)
        used[v] = 1;
    for (std::size_t v = 0; v < used.size(); ++v)
        if (used[v] != 0 && !unowned(tile.mesh.sourceIndex[v], width, height))
            ++tile.coveredCells;
    tile.maxError = 0.0;
    tile.sumSquares = 0.0;
}

/// Every valid cell of the tile a vertex: the tile's Delaunay TIN of them at their centres (as
/// the refiner's TINs stand), sourceIndex = the tile's cell index; the cells flagged as
/// vertices for the measure.
TinMesh triangulateEveryCell(const HeightGrid& grid, CellFlags& flags, unsigned threads) {
    std::vector<Point3> points;
    std::vector<std::uint32_t> cellOf;
    for (std::size_t cell = 0; cell < flags.size(); ++cell) {
        if ((flags[cell] & kCellNoData) != 0)
            continue;
        const Point2 centre = grid.cellCentre(static_cast<std::uint64_t>(cell));
        points.push_back({centre.x, centre.y, double{grid.z[cell]}});
        cellOf.push_back(static_cast<std::uint32_t>(cell));
        flags[cell] |= kCellVertex;
    }
    TriangulationOptions options;
    options.threads = threads;
    TinMesh mesh = triangulate(points, options).mesh;
    for (std::uint32_t& source : mesh.sourceIndex)
        source = cellOf[source];
    return mesh;
}

} // namespace

std::vector<std::uint32_t> keptSideCells(const HeightGrid& tile, double maxError) {
    std::vector<std::uint32_t> kept;
    std::vector<float> elevations;
    for (const std::vector<std::uint32_t>& side :
         sidesOf(static_cast<std::size_t>(tile.width), static_cast<std::size_t>(tile.height))) {
        elevations.clear();
        for (const std::uint32_t cell : side)
            elevations.push_back(tile.z[cell]);
        for (const std::uint32_t k :
             keptBorderCells(elevations, sideTolerance(elevations, maxError)))
            kept.push_back(side[k]);
    }
    return kept;
}

double sideTolerance(std::span<const float> side, double maxError) {
    double largest = 0.0;
    for (const float z : side)
        if (!std::isnan(z))
            largest = std::max(largest, std::abs(double{z}));
    return std::max(0.0, maxError - (1e-7 * (largest + maxError) + 1e-6));
}

TileRefinement refineOneTile(CellSource& cells, const TileGrid& tiles, std::size_t tile,
                             const TiledRefineOptions& options, RoundWorkers& workers,
                             const ProgressCallback& progress) {
    if (options.cellPositions)
        return refineProjectedTile(cells, tiles, tile, options, workers, progress);
    const std::size_t tileRow = tile / tiles.tileColumns();
    const std::size_t tileColumn = tile % tiles.tileColumns();
    TileCells read = readTileCells(cells, tiles, tile, options);
    const HeightGrid& grid = read.grid;
    CellFlags& flags = read.flags;
    const CellWindow& inner = read.inner;

    TileRefinement result;
    const UnownedSides unowned = tiles.unownedSidesOf(tile);
    countCells(flags, inner.width(), inner.height(), unowned, result);
    if (!validCellsSpanArea(grid)) {
        coverTheSides(grid, tileRow > 0, tileColumn > 0, unowned, result); // covers none
        return result;
    }
    if (options.everyCell) {
        result.mesh = triangulateEveryCell(grid, flags, workers.size());
        if (options.validate)
            checkExactlyDelaunay(result.mesh, "a tile's TIN");
        dropHoles(flags, trianglesOverHoles(grid, flags, result.mesh, workers.size()), result);
        measureEveryCell(grid, unowned, result);
        coverTheSides(grid, tileRow > 0, tileColumn > 0, unowned, result);
        return result;
    }
    std::vector<std::uint32_t> seeds = seedTheSides(grid, *options.maxError, flags);

    GreedyRefiner refiner(grid, {}, flags, options, workers);
    refiner.setSeedCells(std::move(seeds));
    try {
        refiner.run(progress);
    } catch (const InvalidInputError& error) { // a share of a limit below the hull's corners
        throw InvalidInputError("Refiner: tile " + std::to_string(tileRow) + ", " +
                                std::to_string(tileColumn) + ": " + error.what() +
                                " (the tile's share of the limit)");
    }
    std::vector<TriId> slots;
    result.mesh = refiner.extractInCellOrder(&slots);
    // While the sides' cells are still frozen (dropHoles thaws them).
    const std::vector<std::uint8_t> drop =
        refiner.coverStrandedVertices(result.mesh, slots, 0, progress);
    copyRefinerCounts(refiner, result);
    result.stop = refiner.stop();
    checkTheShares(result.mesh, options, tileRow, tileColumn);
    if (options.validate)
        checkExactlyDelaunay(result.mesh, "a tile's TIN");
    dropHoles(flags, drop, result);
    measure(grid, flags, unowned, workers.size(), result);
    coverTheSides(grid, tileRow > 0, tileColumn > 0, unowned, result);
    return result;
}

} // namespace terratin::detail

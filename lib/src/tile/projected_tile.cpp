#include "projected_tile.hpp"

#include "one_tile.hpp"
#include "projected_sides.hpp"
#include "tile_cells.hpp"

#include "../parallel/round_workers.hpp"
#include "../refine/cell_completion.hpp"
#include "../refine/greedy_refiner.hpp"

#include "terratin/constrain/constrained_validation.hpp"
#include "terratin/constrain/insert_constraints.hpp"
#include "terratin/error.hpp"
#include "terratin/geometry/predicates.hpp"
#include "terratin/triangulate/mesh_filter.hpp"
#include "terratin/triangulate/triangulate.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <utility>

namespace terratin::detail {

namespace {

constexpr std::uint32_t kNotAVertex = std::numeric_limits<std::uint32_t>::max();

/// A tile's cells with their positions, and those of the cells one beyond it, which the choice
/// of its sides' vertices needs.
struct PlacedTile {
    TileCells read;
    /// The tile grown by one cell (within the raster), and its cells' positions.
    CellWindow around;
    std::vector<Point2> aroundAt;
    /// The tile's cells' positions, row-major.
    std::vector<Point2> at;
    /// +1 where the positions keep the orientation of the pixel frame (column, row), -1 where
    /// they flip it.
    int frameSign = 1;

    [[nodiscard]] std::size_t width() const { return read.inner.width(); }
    [[nodiscard]] std::size_t height() const { return read.inner.height(); }
    /// The position and elevation of the raster's cell (row, column), within `around`.
    [[nodiscard]] Point2 positionAt(std::size_t row, std::size_t column) const {
        return aroundAt[(row - around.rows.first) * around.width() + column - around.columns.first];
    }
    [[nodiscard]] float elevationAt(std::size_t row, std::size_t column) const {
        return read.margin.z[(row - read.outer.rows.first) * read.outer.width() + column -
                             read.outer.columns.first];
    }
};

PlacedTile placeTile(CellSource& cells, const TileGrid& tiles, std::size_t tile,
                     const RefineOptions& options) {
    PlacedTile placed{readTileCells(cells, tiles, tile, options, 1), {}, {}, {}, 1};
    placed.around = grown(placed.read.inner, 1, static_cast<std::size_t>(cells.width()),
                          static_cast<std::size_t>(cells.height()));
    HeightGrid shape;
    shape.width = static_cast<int>(placed.around.width());
    shape.height = static_cast<int>(placed.around.height());
    shape.geoTransform = cells.geoTransform();
    shape.firstRow = static_cast<int>(placed.around.rows.first);
    shape.firstColumn = static_cast<int>(placed.around.columns.first);
    placed.aroundAt = options.cellPositions(shape);
    if (placed.aroundAt.size() != shape.cellCount())
        throw Error("Refiner: " + std::to_string(placed.aroundAt.size()) + " positions for " +
                    std::to_string(shape.cellCount()) + " cells of a tile");
    for (const Point2& p : placed.aroundAt)
        if (!std::isfinite(p.x) || !std::isfinite(p.y))
            throw InvalidInputError("Refiner: a cell position is not finite");
    placed.at = cellsWithin(placed.aroundAt, placed.around, placed.read.inner);
    if (placed.around.width() > 1 && placed.around.height() > 1) {
        const std::size_t r = placed.around.rows.first;
        const std::size_t c = placed.around.columns.first;
        placed.frameSign =
            predicates::orient2d(placed.positionAt(r, c), placed.positionAt(r, c + 1),
                                 placed.positionAt(r + 1, c)) < 0.0
                ? -1
                : 1;
    }
    return placed;
}

/// Side k of the tile (sidesOf's order: top, bottom, left, right) as both its tiles see it.
ProjectedSide projectedSide(const PlacedTile& tile, std::size_t k, std::size_t rasterWidth,
                            std::size_t rasterHeight) {
    const bool alongRow = k < 2;
    const CellRange across = alongRow ? tile.read.inner.rows : tile.read.inner.columns;
    const CellRange along = alongRow ? tile.read.inner.columns : tile.read.inner.rows;
    const std::size_t line = k % 2 == 0 ? across.first : across.last;
    const std::size_t lines = alongRow ? rasterHeight : rasterWidth;
    const auto cellAt = [&](std::size_t lineIndex, std::size_t i) {
        return alongRow ? std::pair{lineIndex, i} : std::pair{i, lineIndex};
    };
    ProjectedSide side;
    // Along a row, the next row lies to the left in the pixel frame; along a column, the next
    // column lies to the right.
    side.afterSign = alongRow ? tile.frameSign : -tile.frameSign;
    for (std::size_t i = along.first; i <= along.last; ++i) {
        const auto [row, column] = cellAt(line, i);
        side.z.push_back(tile.elevationAt(row, column));
        side.at.push_back(tile.positionAt(row, column));
        if (line > 0) {
            const auto [r, c] = cellAt(line - 1, i);
            side.beforeZ.push_back(tile.elevationAt(r, c));
            side.before.push_back(tile.positionAt(r, c));
        }
        if (line + 1 < lines) {
            const auto [r, c] = cellAt(line + 1, i);
            side.afterZ.push_back(tile.elevationAt(r, c));
            side.after.push_back(tile.positionAt(r, c));
        }
    }
    return side;
}

/// Each side's kept cells (sidesOf's order), as the tile's cell indices in increasing order
/// along the side.
std::vector<std::vector<std::uint32_t>> keptSides(const PlacedTile& tile,
                                                  const RefineOptions& options,
                                                  std::size_t rasterWidth,
                                                  std::size_t rasterHeight) {
    const std::vector<std::vector<std::uint32_t>> sides = sidesOf(tile.width(), tile.height());
    std::vector<std::vector<std::uint32_t>> kept(4);
    for (std::size_t k = 0; k < 4; ++k) {
        const ProjectedSide side = projectedSide(tile, k, rasterWidth, rasterHeight);
        const std::optional<double> tolerance =
            options.everyCell ? std::nullopt
                              : std::optional(sideTolerance(side.z, *options.maxError));
        for (const std::uint32_t i : keptProjectedSideCells(side, tolerance))
            kept[k].push_back(sides[k][i]);
    }
    return kept;
}

/// The tile's boundary: its kept side cells in ring order (top left to right, right side down,
/// bottom right to left, left side up: counter-clockwise in the pixel frame, inside on the
/// left), and where two of them are not neighbours along one side, the cells of a convex chain
/// that keeps every valid cell of the tile inside (a corner without data, a side without a kept
/// cell).
class TileRing {
public:
    TileRing(const PlacedTile& tile, const std::vector<std::vector<std::uint32_t>>& kept)
        : m_tile(&tile), m_width(tile.width()), m_height(tile.height()) {
        std::vector<std::uint32_t> order = kept[0];
        order.insert(order.end(), kept[3].begin(), kept[3].end());
        order.insert(order.end(), kept[1].rbegin(), kept[1].rend());
        order.insert(order.end(), kept[2].rbegin(), kept[2].rend());
        order.erase(std::unique(order.begin(), order.end()), order.end());
        if (order.size() > 1 && order.front() == order.back())
            order.pop_back();
        for (std::size_t c = 0; c < tile.at.size(); ++c)
            if (tile.read.grid.isValid(c) && !onSide(static_cast<std::uint32_t>(c)))
                m_interior.push_back(static_cast<std::uint32_t>(c));
        if (order.size() < 2)
            startFromTwo(order);
        for (std::size_t k = 0; k < order.size(); ++k) {
            const std::uint32_t u = order[k];
            const std::uint32_t v = order[(k + 1) % order.size()];
            m_cells.push_back(u);
            m_alongSide.push_back(alongOneSide(u, v));
            if (!m_alongSide.back())
                chainBetween(u, v, outsideOf(u, v, m_interior));
        }
    }

    /// The ring's cells in order; whether the edge from cells[k] to the next runs along one side
    /// between two of its kept cells.
    [[nodiscard]] const std::vector<std::uint32_t>& cells() const { return m_cells; }
    [[nodiscard]] bool alongSide(std::size_t k) const { return m_alongSide[k] != 0; }
    [[nodiscard]] bool onSide(std::uint32_t cell) const {
        const std::size_t row = cell / m_width;
        const std::size_t column = cell % m_width;
        return row == 0 || row + 1 == m_height || column == 0 || column + 1 == m_width;
    }
    /// Exact orientation of cell c against the directed edge u -> v, positive when c lies inside.
    [[nodiscard]] double inward(std::uint32_t u, std::uint32_t v, std::uint32_t c) const {
        const double o = predicates::orient2d(m_tile->at[u], m_tile->at[v], m_tile->at[c]);
        return m_tile->frameSign > 0 ? o : -o;
    }

private:
    /// Whether u -> v follows one side in ring order (both on it, v after u).
    [[nodiscard]] bool alongOneSide(std::uint32_t u, std::uint32_t v) const {
        const std::size_t ur = u / m_width;
        const std::size_t uc = u % m_width;
        const std::size_t vr = v / m_width;
        const std::size_t vc = v % m_width;
        return (ur == 0 && vr == 0 && vc > uc) ||
               (uc + 1 == m_width && vc + 1 == m_width && vr > ur) ||
               (ur + 1 == m_height && vr + 1 == m_height && vc < uc) ||
               (uc == 0 && vc == 0 && vr < ur);
    }

    [[nodiscard]] std::vector<std::uint32_t>
    outsideOf(std::uint32_t u, std::uint32_t v, const std::vector<std::uint32_t>& cells) const {
        std::vector<std::uint32_t> outside;
        for (const std::uint32_t c : cells)
            if (c != u && c != v && inward(u, v, c) < 0.0)
                outside.push_back(c);
        return outside;
    }

    /// Appends the convex chain from u to v (u and v excluded) around `outside` (quickhull:
    /// the farthest cell, the lowest of equals, then each half).
    void chainBetween(std::uint32_t u, std::uint32_t v, const std::vector<std::uint32_t>& outside) {
        if (outside.empty())
            return;
        std::uint32_t farthest = outside.front();
        double farthestDistance = 0.0;
        for (const std::uint32_t c : outside) {
            const double distance = -inward(u, v, c);
            if (distance > farthestDistance) {
                farthest = c;
                farthestDistance = distance;
            }
        }
        const std::vector<std::uint32_t> before = outsideOf(u, farthest, outside);
        const std::vector<std::uint32_t> after = outsideOf(farthest, v, outside);
        chainBetween(u, farthest, before);
        m_cells.push_back(farthest);
        m_alongSide.push_back(0);
        chainBetween(farthest, v, after);
    }

    /// With fewer than two kept side cells, a second cell to start the ring from: the valid
    /// cell farthest from the first (the first valid interior cell when none is kept).
    void startFromTwo(std::vector<std::uint32_t>& order) const {
        if (order.empty() && !m_interior.empty())
            order.push_back(m_interior.front());
        if (order.empty())
            return;
        const Point2 first = m_tile->at[order.front()];
        std::uint32_t farthest = order.front();
        double farthestDistance = 0.0;
        for (const std::uint32_t c : m_interior) {
            const double dx = m_tile->at[c].x - first.x;
            const double dy = m_tile->at[c].y - first.y;
            if (dx * dx + dy * dy > farthestDistance) {
                farthest = c;
                farthestDistance = dx * dx + dy * dy;
            }
        }
        if (farthest != order.front())
            order.push_back(farthest);
    }

    const PlacedTile* m_tile;
    std::size_t m_width;
    std::size_t m_height;
    std::vector<std::uint32_t> m_interior; // valid cells on no side
    std::vector<std::uint32_t> m_cells;
    std::vector<std::uint8_t> m_alongSide;
};

/// For each side cell strictly inside the ring (between two kept cells of its side, on the
/// inner side of their chord), 1: such a cell may become a vertex of this tile alone. 0 for the
/// others, which lie on a chord (both tiles' boundary) or in the neighbour's tile.
std::vector<std::uint8_t> sideCellsInside(const TileRing& ring, const HeightGrid& grid) {
    std::vector<std::uint8_t> inside(grid.cellCount(), 0);
    const std::vector<std::uint32_t>& cells = ring.cells();
    const auto width = static_cast<std::uint32_t>(grid.width);
    for (std::size_t k = 0; k < cells.size(); ++k) {
        if (!ring.alongSide(k))
            continue;
        const std::uint32_t u = cells[k];
        const std::uint32_t v = cells[(k + 1) % cells.size()];
        const bool alongRow = u / width == v / width;
        const std::uint32_t step = alongRow ? 1 : width;
        for (std::uint32_t c = std::min(u, v) + step; c < std::max(u, v); c += step)
            if (grid.isValid(c) && ring.inward(u, v, c) > 0.0)
                inside[c] = 1;
    }
    return inside;
}

std::uint64_t edgeKey(std::uint32_t from, std::uint32_t to) {
    return (std::uint64_t{from} << 32U) | to;
}

/// The ring's edges in `tin` (its chains, which the cells inserted on them split), as sorted
/// keys directed with the tile on their left at the positions (where the pixel frame's ring has
/// it when `frameSign` is +1).
std::vector<std::uint64_t> ringEdges(const ConstrainedTin& tin, int frameSign) {
    std::vector<std::uint64_t> edges;
    for (const std::vector<std::uint32_t>& chain : tin.chains)
        for (std::size_t i = 0; i + 1 < chain.size(); ++i)
            edges.push_back(frameSign > 0 ? edgeKey(chain[i], chain[i + 1])
                                          : edgeKey(chain[i + 1], chain[i]));
    std::sort(edges.begin(), edges.end());
    return edges;
}

/// 1 for every triangle of `tin` outside the tile's ring: the triangles on the outer side of a
/// ring edge and every triangle reached from them across unconstrained edges.
std::vector<std::uint8_t> trianglesOutsideRing(const ConstrainedTin& tin, int frameSign) {
    const std::vector<std::uint64_t> ring = ringEdges(tin, frameSign);
    const TinMesh& mesh = tin.mesh;
    std::vector<std::uint8_t> outside(mesh.triangleCount(), 0);
    std::vector<std::size_t> pending;
    for (std::size_t t = 0; t < mesh.triangleCount(); ++t)
        for (std::size_t e = 0; e < 3; ++e) {
            const std::uint32_t a = mesh.triangles[3 * t + e];
            const std::uint32_t b = mesh.triangles[3 * t + (e + 1) % 3];
            // A counter-clockwise triangle lies on the left of its edge a -> b, so on the right
            // of the ring edge b -> a.
            if (tin.constrained[3 * t + e] != 0 && outside[t] == 0 &&
                std::binary_search(ring.begin(), ring.end(), edgeKey(b, a))) {
                outside[t] = 1;
                pending.push_back(t);
            }
        }
    while (!pending.empty()) {
        const std::size_t t = pending.back();
        pending.pop_back();
        for (std::size_t e = 0; e < 3; ++e) {
            const std::int32_t n = mesh.neighbours[3 * t + e];
            if (n == kNoNeighbour || tin.constrained[3 * t + e] != 0 ||
                outside[static_cast<std::size_t>(n)] != 0)
                continue;
            outside[static_cast<std::size_t>(n)] = 1;
            pending.push_back(static_cast<std::size_t>(n));
        }
    }
    return outside;
}

/// The tile's first TIN at its positions: every valid cell with options.everyCell, else the
/// refiner's, from the ring's cells and the valid cells on no side (the sides' other cells are
/// decided by the ring: kept out of the refiner as cells without data).
TinMesh firstTin(const PlacedTile& tile, const TileRing& ring, const RefineOptions& options,
                 RoundWorkers& workers, const ProgressCallback& progress, TileRefinement& result) {
    const HeightGrid& grid = tile.read.grid;
    if (options.everyCell) {
        std::vector<Point3> points;
        std::vector<std::uint32_t> cellOf;
        for (std::uint32_t cell = 0; cell < grid.cellCount(); ++cell)
            if (grid.isValid(cell)) {
                points.push_back({tile.at[cell].x, tile.at[cell].y, double{grid.z[cell]}});
                cellOf.push_back(cell);
            }
        TriangulationOptions triangulation;
        triangulation.threads = workers.size();
        TinMesh mesh = triangulate(points, triangulation).mesh;
        for (std::uint32_t& source : mesh.sourceIndex)
            source = cellOf[source];
        return mesh;
    }
    HeightGrid refined = grid;
    CellFlags flags = tile.read.flags;
    std::vector<std::uint8_t> inRing(grid.cellCount(), 0);
    for (const std::uint32_t cell : ring.cells())
        inRing[cell] = 1;
    for (std::uint32_t cell = 0; cell < grid.cellCount(); ++cell)
        if (ring.onSide(cell) && inRing[cell] == 0) {
            refined.z[cell] = std::numeric_limits<float>::quiet_NaN();
            flags[cell] |= kCellNoData;
        }
    GreedyRefiner refiner(refined, tile.at, flags, options, workers);
    refiner.setSeedCells(ring.cells());
    refiner.run(progress);
    copyRefinerCounts(refiner, result);
    result.stop = refiner.stop();
    return refiner.extractInCellOrder();
}

/// The ring inserted into `mesh` (its vertices cells of a tile of `cellCount`) as constraints.
/// Throws Error where the ring crosses itself or
/// a vertex lies on a side's chord (which the choice of the sides' cells rules out).
ConstrainedTin constrainToRing(TinMesh mesh, const TileRing& ring, std::size_t cellCount) {
    std::vector<std::uint32_t> vertexOfCell(cellCount, kNotAVertex);
    for (std::uint32_t v = 0; v < mesh.vertexCount(); ++v) {
        const std::uint32_t cell = mesh.sourceIndex[v];
        if (cell >= cellCount)
            throw Error("Tiles: a vertex of a tile's TIN is no cell of the tile");
        vertexOfCell[cell] = v;
    }
    const std::vector<std::uint32_t>& cells = ring.cells();
    ConstraintSet set;
    for (std::size_t k = 0; k < cells.size(); ++k) {
        const std::uint32_t u = cells[k];
        const std::uint32_t v = cells[(k + 1) % cells.size()];
        if (vertexOfCell[u] == kNotAVertex || vertexOfCell[v] == kNotAVertex)
            throw Error("Tiles: a cell of a tile's boundary is no vertex of its TIN");
        set.segments.push_back({vertexOfCell[u], vertexOfCell[v]});
    }
    ConstrainedTin tin = insertConstraints(std::move(mesh), set);
    if (tin.intersections > 0 || tin.addedPoints > 0)
        throw Error("Tiles: a tile's boundary crosses itself");
    for (std::size_t k = 0; k < tin.chains.size(); ++k)
        if (ring.alongSide(k) && tin.chains[k].size() != 2)
            throw Error("Tiles: a vertex lies on the chord between two side cells of a tile");
    return tin;
}

/// For each of `cells` (each a vertex of `mesh`, ascending), 0 when a triangle that `drop`
/// keeps uses its vertex (a vertex's error), else NaN: full resolution's measure.
std::vector<double> verticesKept(const TinMesh& mesh, const std::vector<std::uint8_t>& drop,
                                 const std::vector<std::size_t>& cells) {
    std::vector<std::uint8_t> used(mesh.vertexCount(), 0);
    for (std::size_t t = 0; t < mesh.triangleCount(); ++t)
        if (drop[t] == 0)
            for (std::size_t i = 0; i < 3; ++i)
                used[mesh.triangles[3 * t + i]] = 1;
    std::vector<double> squared(cells.size(), std::numeric_limits<double>::quiet_NaN());
    for (std::size_t v = 0; v < mesh.vertexCount(); ++v) {
        const auto at = std::lower_bound(cells.begin(), cells.end(), mesh.sourceIndex[v]);
        if (used[v] != 0 && at != cells.end() && *at == mesh.sourceIndex[v])
            squared[static_cast<std::size_t>(at - cells.begin())] = 0.0;
    }
    return squared;
}

/// `progress` for a part of the tile's work, from `start` for `share` of it.
ProgressCallback partOf(const ProgressCallback& progress, double start, double share) {
    if (!progress)
        return {};
    return [progress, start, share](double fraction, std::string_view message) {
        return progress(start + share * fraction, message);
    };
}

/// The tile's figures from each valid cell's squared error in its kept triangles (NaN: none).
void countFromErrors(const std::vector<std::size_t>& cells, const std::vector<double>& squared,
                     const HeightGrid& grid, bool topShared, bool leftShared, UnownedSides unowned,
                     TileRefinement& result) {
    const auto width = static_cast<std::size_t>(grid.width);
    const auto height = static_cast<std::size_t>(grid.height);
    for (std::size_t i = 0; i < cells.size(); ++i) {
        const std::size_t cell = cells[i];
        const bool covered = !std::isnan(squared[i]);
        const bool later = unowned(cell, width, height);
        if (!later && covered) {
            ++result.coveredCells;
            result.sumSquares += squared[i];
        }
        const bool shared = (topShared && cell / width == 0) || (leftShared && cell % width == 0);
        if (later && covered)
            result.coveredForLaterTiles.push_back({static_cast<std::uint32_t>(cell), squared[i]});
        else if (!later && shared && !covered)
            result.uncoveredSharedSides.push_back(static_cast<std::uint32_t>(cell));
    }
}

} // namespace

std::vector<std::uint32_t> keptProjectedSideCells(CellSource& cells, const TileGrid& tiles,
                                                  std::size_t tile, const RefineOptions& options) {
    const PlacedTile placed = placeTile(cells, tiles, tile, options);
    std::vector<std::uint32_t> kept;
    for (const std::vector<std::uint32_t>& side :
         keptSides(placed, options, static_cast<std::size_t>(cells.width()),
                   static_cast<std::size_t>(cells.height())))
        kept.insert(kept.end(), side.begin(), side.end());
    std::sort(kept.begin(), kept.end());
    kept.erase(std::unique(kept.begin(), kept.end()), kept.end());
    return kept;
}

TileRefinement refineProjectedTile(CellSource& cells, const TileGrid& tiles, std::size_t tile,
                                   const RefineOptions& options, RoundWorkers& workers,
                                   const ProgressCallback& progress) {
    const std::size_t tileRow = tile / tiles.tileColumns();
    const std::size_t tileColumn = tile % tiles.tileColumns();
    const PlacedTile placed = placeTile(cells, tiles, tile, options);
    const HeightGrid& grid = placed.read.grid;
    const UnownedSides unowned = tiles.unownedSidesOf(tile);
    TileRefinement result;
    countCells(placed.read.flags, placed.width(), placed.height(), unowned, result);

    std::vector<std::size_t> validCells;
    CompletionRules rules;
    for (std::size_t cell = 0; cell < grid.cellCount(); ++cell) {
        if (grid.isValid(cell))
            validCells.push_back(cell);
        else if ((placed.read.flags[cell] & kCellOpenHole) != 0)
            rules.openHoleCells.push_back(cell);
    }
    if (!validCellsSpanArea(grid)) { // no triangle: every shared side cell uncovered
        countFromErrors(
            validCells,
            std::vector<double>(validCells.size(), std::numeric_limits<double>::quiet_NaN()), grid,
            tileRow > 0, tileColumn > 0, unowned, result);
        return result;
    }
    // At full resolution every valid cell is a vertex already: only the holes are located.
    if (!options.everyCell)
        rules.measuredCells = validCells;
    const TileRing ring(placed, keptSides(placed, options, static_cast<std::size_t>(cells.width()),
                                          static_cast<std::size_t>(cells.height())));
    TinMesh mesh = firstTin(placed, ring, options, workers, partOf(progress, 0.0, 0.8), result);
    checkTheShares(mesh, options, tileRow, tileColumn);
    ConstrainedTin tin = constrainToRing(std::move(mesh), ring, grid.cellCount());

    const std::vector<std::uint8_t> insideSides = sideCellsInside(ring, grid);
    rules.outsideArea = [frameSign = placed.frameSign](const ConstrainedTin& constrained) {
        return trianglesOutsideRing(constrained, frameSign);
    };
    rules.insertable = [&](std::size_t cell) {
        return !ring.onSide(static_cast<std::uint32_t>(cell)) || insideSides[cell] != 0;
    };
    rules.coverStrandedVertices = true;
    rules.keepCellErrors = true;
    const Completion completion = completeWithCells(grid, placed.at, tin, rules, options,
                                                    workers.size(), partOf(progress, 0.8, 0.2));
    if (completion.limitReached && result.stop == RefineStop::ErrorReached)
        result.stop = options.maxPoints ? RefineStop::PointLimit : RefineStop::TriangleLimit;
    if (options.validate) {
        const ConstrainedValidation validation = validateConstrainedDelaunay(tin);
        if (!validation.ok())
            throw Error("Refiner: a tile's TIN is not constrained Delaunay: " +
                        (validation.problems.empty() ? std::string("(no detail)")
                                                     : validation.problems.front()));
    }
    const std::vector<double> squaredErrors =
        options.everyCell ? verticesKept(tin.mesh, completion.drop, validCells)
                          : completion.squaredErrors;
    result.mesh = std::move(tin.mesh);
    dropTriangles(result.mesh, completion.drop);
    result.droppedTriangles = completion.holeTriangles;
    result.maxError = completion.maxError;
    countFromErrors(validCells, squaredErrors, grid, tileRow > 0, tileColumn > 0, unowned, result);
    return result;
}

} // namespace terratin::detail

#include "placed_tile.hpp"

#include "one_tile.hpp"
#include "projected_sides.hpp"

#include "terratin/error.hpp"
#include "terratin/geometry/predicates.hpp"

#include <cmath>
#include <optional>
#include <string>
#include <utility>

namespace terratin::detail {

namespace {

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

} // namespace

PlacedTile placeTile(CellSource& cells, const TileGrid& tiles, std::size_t tile,
                     const TiledRefineOptions& options) {
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

std::vector<std::vector<std::uint32_t>> keptSides(const PlacedTile& tile,
                                                  const TiledRefineOptions& options,
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

} // namespace terratin::detail

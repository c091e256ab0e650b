#include "tile_cells.hpp"

#include "../refine/grid_scan.hpp"

#include "terratin/error.hpp"

#include <string>

namespace terratin::detail {

namespace {

/// The grid of `inner` out of `grid`, which holds `outer`.
HeightGrid gridWithin(const HeightGrid& grid, const CellWindow& outer, const CellWindow& inner) {
    HeightGrid within;
    within.width = static_cast<int>(inner.width());
    within.height = static_cast<int>(inner.height());
    within.geoTransform = grid.geoTransform;
    within.firstRow = grid.firstRow + static_cast<int>(inner.rows.first - outer.rows.first);
    within.firstColumn =
        grid.firstColumn + static_cast<int>(inner.columns.first - outer.columns.first);
    within.z = cellsWithin(grid.z, outer, inner);
    return within;
}

} // namespace

CellWindow grown(const CellWindow& inner, std::size_t margin, std::size_t width,
                 std::size_t height) {
    const auto grow = [margin](CellRange range, std::size_t cells) {
        return CellRange{range.first - std::min(range.first, margin),
                         std::min(range.last + margin, cells - 1)};
    };
    return {grow(inner.rows, height), grow(inner.columns, width)};
}

TileCells readTileCells(CellSource& cells, const TileGrid& tiles, std::size_t tile,
                        const RefineOptions& options, std::size_t leastMargin) {
    TileCells read;
    const std::size_t tileRow = tile / tiles.tileColumns();
    read.inner = {tiles.rowsOf(tileRow), tiles.columnsOf(tile % tiles.tileColumns())};
    read.outer = grown(
        read.inner, std::max(options.fillHoles ? std::size_t{0} : options.maxHole, leastMargin),
        static_cast<std::size_t>(cells.width()), static_cast<std::size_t>(cells.height()));
    read.margin = cells.window(
        static_cast<int>(read.outer.rows.first), static_cast<int>(read.outer.height()),
        static_cast<int>(read.outer.columns.first), static_cast<int>(read.outer.width()));
    std::size_t ignored = 0;
    read.flags =
        cellsWithin(makeCellFlags(read.margin, options.maxHole, options.fillHoles, ignored),
                    read.outer, read.inner);
    read.grid = gridWithin(read.margin, read.outer, read.inner);
    return read;
}

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

std::vector<std::vector<std::uint32_t>> sidesOf(std::size_t width, std::size_t height) {
    std::vector<std::vector<std::uint32_t>> sides(4);
    for (std::size_t column = 0; column < width; ++column) {
        sides[0].push_back(static_cast<std::uint32_t>(column));
        sides[1].push_back(static_cast<std::uint32_t>((height - 1) * width + column));
    }
    for (std::size_t row = 0; row < height; ++row) {
        sides[2].push_back(static_cast<std::uint32_t>(row * width));
        sides[3].push_back(static_cast<std::uint32_t>(row * width + width - 1));
    }
    return sides;
}

void countCells(const CellFlags& flags, std::size_t width, std::size_t height, UnownedSides unowned,
                TileRefinement& tile) {
    for (std::size_t cell = 0; cell < flags.size(); ++cell) {
        if (unowned(cell, width, height))
            continue;
        tile.validCells += (flags[cell] & kCellNoData) == 0 ? 1U : 0U;
        tile.openHoleCells += (flags[cell] & kCellOpenHole) != 0 ? 1U : 0U;
    }
}

void checkTheShares(const TinMesh& mesh, const RefineOptions& options, std::size_t tileRow,
                    std::size_t tileColumn) {
    const auto refuse = [&](const std::string& what, std::size_t share, std::size_t kept) {
        throw InvalidInputError("Refiner: tile " + std::to_string(tileRow) + ", " +
                                std::to_string(tileColumn) + " gets " + std::to_string(share) +
                                " " + what + " of the limit, fewer than the " +
                                std::to_string(kept) + " its hull and sides keep within the " +
                                "maximum error; raise the limit or the maximum error, or make "
                                "the tiles larger");
    };
    if (options.maxPoints && mesh.vertexCount() > *options.maxPoints)
        refuse("points", *options.maxPoints, mesh.vertexCount());
    if (options.maxTriangles && mesh.triangleCount() > *options.maxTriangles)
        refuse("triangles", *options.maxTriangles, mesh.triangleCount());
}

} // namespace terratin::detail

#pragma once
/// @file
/// A tile's cells as its refinement reads them (one_tile.hpp, projected_tile.hpp): the window of
/// the raster it covers, read with a margin that decides its open holes, and the flags of its
/// cells; and what both kinds of tile count and check.

#include "tile_grid.hpp"
#include "tile_refinement.hpp"

#include "../refine/cell_flags.hpp"

#include "terratin/refine/refine.hpp"
#include "terratin/tile/cell_source.hpp"

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace terratin::detail {

/// A rectangle of cells, in the grid's rows and columns (both ends included).
struct CellWindow {
    CellRange rows;
    CellRange columns;

    [[nodiscard]] std::size_t width() const { return columns.count(); }
    [[nodiscard]] std::size_t height() const { return rows.count(); }
};

/// `inner` grown by `margin` cells on every side, within a grid of width x height cells.
CellWindow grown(const CellWindow& inner, std::size_t margin, std::size_t width,
                 std::size_t height);

/// The cells of `inner` out of a row-major array over `outer`, row-major over `inner`.
template <class Array>
Array cellsWithin(const Array& cells, const CellWindow& outer, const CellWindow& inner) {
    Array copy(inner.width() * inner.height());
    for (std::size_t row = 0; row < inner.height(); ++row) {
        const std::size_t from = (inner.rows.first - outer.rows.first + row) * outer.width() +
                                 (inner.columns.first - outer.columns.first);
        std::copy_n(cells.begin() + static_cast<std::ptrdiff_t>(from), inner.width(),
                    copy.begin() + static_cast<std::ptrdiff_t>(row * inner.width()));
    }
    return copy;
}

/// A tile's cells: `grid` and `flags` over the tile (`inner`), and `margin`, the raster's cells
/// over `outer`, the tile grown by the margin read.
struct TileCells {
    CellWindow inner;
    CellWindow outer;
    HeightGrid margin;
    HeightGrid grid;
    CellFlags flags;
};

/// Reads tile `tile` with a margin of options.maxHole cells (none with fillHoles), at least
/// `leastMargin`: a nodata region of more than maxHole cells has that many within maxHole cells
/// of any of its cells, so the margin decides the tile's open holes as the whole grid would.
TileCells readTileCells(CellSource& cells, const TileGrid& tiles, std::size_t tile,
                        const RefineOptions& options, std::size_t leastMargin = 0);

/// Whether the valid cells of `grid` span an area (three of them not on one line), which the
/// refiner needs. Exact: pixel coordinates are integers.
bool validCellsSpanArea(const HeightGrid& grid);

/// The cells of the four sides of a width x height tile (row-major tile indices), each in
/// increasing row or column order, as the tile on the other side reads them too: top, bottom,
/// left, right.
std::vector<std::vector<std::uint32_t>> sidesOf(std::size_t width, std::size_t height);

/// Counts the owned valid and open hole cells of the tile.
void countCells(const CellFlags& flags, std::size_t width, std::size_t height, UnownedSides unowned,
                TileRefinement& tile);

/// Refuses a tile whose sides and hull alone took more than its share of a point or triangle
/// limit: the whole would pass the limit.
void checkTheShares(const TinMesh& mesh, const RefineOptions& options, std::size_t tileRow,
                    std::size_t tileColumn);

} // namespace terratin::detail

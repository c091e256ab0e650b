#pragma once
/// @file
/// How a DEM is cut into seam-free tiles: along each axis, ranges of cells
/// that share their end cells with the neighbouring range, so that the cell line on a border
/// belongs to both tiles and its vertices are decided once (border_profile.hpp).

#include <algorithm>
#include <cstddef>

namespace terratin::detail {

/// Cells first..last of one axis, both included.
struct CellRange {
    std::size_t first = 0;
    std::size_t last = 0;

    [[nodiscard]] std::size_t count() const { return last - first + 1; }
    friend bool operator==(const CellRange&, const CellRange&) = default;
};

/// Where a tile lies in the grid, in cells.
struct TilePlace {
    std::size_t firstRow = 0;
    std::size_t firstColumn = 0;
    std::size_t width = 0;
    std::size_t height = 0;
};

/// The cells of a tile that belong to its neighbours, so that each cell of the grid has one
/// owner: its bottom side and its right one belong to the tiles below and to the right, unless
/// they are the grid's (tile_refinement.hpp).
struct UnownedSides {
    bool bottom = false;
    bool right = false;

    /// Whether cell `cell` of a width x height tile (row-major) is on an unowned side.
    [[nodiscard]] bool operator()(std::size_t cell, std::size_t width, std::size_t height) const {
        return (bottom && cell / width == height - 1) || (right && cell % width == width - 1);
    }
};

/// The tiles of a grid of `width` x `height` cells: tile column k spans the cells
/// k * tileSize .. min((k + 1) * tileSize, width - 1), and likewise for rows, so neighbouring
/// tiles share one column (or row) of cells and the last tile holds what is left (as little as
/// one cell beyond its border). A grid of one cell across is one tile of one cell.
class TileGrid {
public:
    /// Throws std::invalid_argument when a size is 0.
    TileGrid(std::size_t width, std::size_t height, std::size_t tileSize);

    [[nodiscard]] std::size_t tileColumns() const { return countAlong(m_width); }
    [[nodiscard]] std::size_t tileRows() const { return countAlong(m_height); }
    [[nodiscard]] std::size_t tileCount() const { return tileColumns() * tileRows(); }
    [[nodiscard]] CellRange columnsOf(std::size_t tileColumn) const {
        return rangeAlong(m_width, tileColumn);
    }
    [[nodiscard]] CellRange rowsOf(std::size_t tileRow) const {
        return rangeAlong(m_height, tileRow);
    }
    /// Where tile `tile` lies, the tiles numbered row by row.
    [[nodiscard]] TilePlace placeOf(std::size_t tile) const {
        const CellRange rows = rowsOf(tile / tileColumns());
        const CellRange columns = columnsOf(tile % tileColumns());
        return {rows.first, columns.first, columns.count(), rows.count()};
    }
    /// Which sides of tile `tile` its neighbours own.
    [[nodiscard]] UnownedSides unownedSidesOf(std::size_t tile) const {
        return {tile / tileColumns() + 1 < tileRows(), tile % tileColumns() + 1 < tileColumns()};
    }
    /// The tile that owns the grid's cell (row, column) by that rule: the last tile of those
    /// holding it.
    [[nodiscard]] std::size_t ownerOf(std::size_t row, std::size_t column) const {
        return std::min(row / m_tileSize, tileRows() - 1) * tileColumns() +
               std::min(column / m_tileSize, tileColumns() - 1);
    }

private:
    [[nodiscard]] std::size_t countAlong(std::size_t cells) const;
    [[nodiscard]] CellRange rangeAlong(std::size_t cells, std::size_t tile) const;

    std::size_t m_width;
    std::size_t m_height;
    std::size_t m_tileSize;
};

} // namespace terratin::detail

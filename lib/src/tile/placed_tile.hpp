#pragma once
/// @file
/// A tile of a tiled refinement at projected positions (projected_tile.hpp), placed: its cells
/// and the cells one beyond it at their positions (TileOptions::cellPositions), and the cells
/// its sides keep, which each side's cells alone decide (projected_sides.hpp), so that both
/// tiles of a side keep the same.

#include "tile_cells.hpp"
#include "tile_grid.hpp"
#include "tiled_refine_options.hpp"

#include "terratin/geometry/point.hpp"
#include "terratin/refine/refine.hpp"
#include "terratin/tile/cell_source.hpp"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace terratin::detail {

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

/// Tile `tile` read with a margin of one cell, its cells and their neighbours placed at
/// options.cellPositions. Throws Error when the positions do not match the cells,
/// InvalidInputError when one is not finite.
PlacedTile placeTile(CellSource& cells, const TileGrid& tiles, std::size_t tile,
                     const TiledRefineOptions& options);

/// Each side's kept cells (sidesOf's order), as the tile's cell indices in increasing order
/// along the side.
std::vector<std::vector<std::uint32_t>> keptSides(const PlacedTile& tile,
                                                  const TiledRefineOptions& options,
                                                  std::size_t rasterWidth,
                                                  std::size_t rasterHeight);

} // namespace terratin::detail

#include "tile_grid.hpp"

#include <algorithm>
#include <stdexcept>

namespace terratin::detail {

TileGrid::TileGrid(std::size_t width, std::size_t height, std::size_t tileSize)
    : m_width(width), m_height(height), m_tileSize(tileSize) {
    if (width == 0 || height == 0 || tileSize == 0)
        throw std::invalid_argument("TileGrid: the grid and the tiles need at least one cell");
}

std::size_t TileGrid::countAlong(std::size_t cells) const {
    // cells - 1 intervals between cell centres, tileSize per tile; one tile for a single cell.
    return std::max<std::size_t>(1, (cells - 1 + m_tileSize - 1) / m_tileSize);
}

CellRange TileGrid::rangeAlong(std::size_t cells, std::size_t tile) const {
    if (tile >= countAlong(cells))
        throw std::out_of_range("TileGrid: no such tile");
    const std::size_t first = tile * m_tileSize;
    return {first, std::min(first + m_tileSize, cells - 1)};
}

} // namespace terratin::detail

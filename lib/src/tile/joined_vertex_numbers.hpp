#pragma once
/// @file
/// The numbers the vertices of seam-free tiles get in the TIN they join into, worked out tile by
/// tile without holding that TIN: the TileMeshMerger numbers its vertices with it, and a TIN
/// written tile by tile numbers them the same way.

#include "tile_grid.hpp"

#include <cstddef>
#include <cstdint>
#include <unordered_map>

namespace terratin::detail {

class JoinedVertexNumbers {
public:
    /// `gridWidth`: the whole grid's width in cells, which numbers its cells.
    explicit JoinedVertexNumbers(std::size_t gridWidth) : m_gridWidth(gridWidth) {}

    struct Number {
        std::uint32_t number = 0;
        /// Whether the vertex is new (numbered count() - 1 now), rather than one that a tile
        /// before gave on a side both share.
        bool isNew = true;
    };

    /// The number of the vertex of the tile at `place` that stands on grid cell `cell`, the
    /// tiles coming in tile order and each tile's vertices in their order: a vertex on a side
    /// of its tile keeps the number the first tile to give it had; any other is new.
    Number number(std::uint32_t cell, const TilePlace& place);

    /// Vertices numbered so far.
    [[nodiscard]] std::uint32_t count() const { return m_count; }

private:
    std::size_t m_gridWidth;
    std::uint32_t m_count = 0;
    /// The number of each side cell met so far, by the grid's cell index: the only part of the
    /// joined TIN kept, a few vertices per side cell of tile.
    std::unordered_map<std::uint32_t, std::uint32_t> m_sideVertices;
};

} // namespace terratin::detail

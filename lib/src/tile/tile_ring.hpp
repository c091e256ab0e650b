#pragma once
/// @file
/// The boundary of a tile at projected positions (projected_tile.hpp), a ring through its
/// sides' kept cells, and the tile's TIN constrained to it: the ring's edges inserted as
/// constraints, the triangles outside it, the side cells only this tile may insert.

#include "placed_tile.hpp"

#include "terratin/constrain/constrained_tin.hpp"
#include "terratin/geometry/height_grid.hpp"
#include "terratin/geometry/predicates.hpp"
#include "terratin/triangulate/tin_mesh.hpp"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace terratin::detail {

/// The tile's boundary: its kept side cells in ring order (top left to right, right side down,
/// bottom right to left, left side up: counter-clockwise in the pixel frame, inside on the
/// left), and where two of them are not neighbours along one side, the cells of a convex chain
/// that keeps every valid cell of the tile inside (a corner without data, a side without a kept
/// cell).
class TileRing {
public:
    /// `kept`: each side's kept cells (keptSides). `tile` outlives the ring.
    TileRing(const PlacedTile& tile, const std::vector<std::vector<std::uint32_t>>& kept);

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
    [[nodiscard]] bool alongOneSide(std::uint32_t u, std::uint32_t v) const;
    /// The cells of `cells` but u and v strictly outside the edge u -> v.
    [[nodiscard]] std::vector<std::uint32_t>
    outsideOf(std::uint32_t u, std::uint32_t v, const std::vector<std::uint32_t>& cells) const;
    /// Appends the convex chain from u to v (u and v excluded) around `outside` (quickhull:
    /// the farthest cell, the lowest of equals, then each half).
    void chainBetween(std::uint32_t u, std::uint32_t v, const std::vector<std::uint32_t>& outside);
    /// With fewer than two kept side cells, a second cell to start the ring from: the valid
    /// cell farthest from the first (the first valid interior cell when none is kept).
    void startFromTwo(std::vector<std::uint32_t>& order) const;

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
std::vector<std::uint8_t> sideCellsInside(const TileRing& ring, const HeightGrid& grid);

/// 1 for every triangle of `tin` outside the tile's ring: the triangles on the outer side of a
/// ring edge and every triangle reached from them across unconstrained edges. `frameSign`:
/// PlacedTile::frameSign.
std::vector<std::uint8_t> trianglesOutsideRing(const ConstrainedTin& tin, int frameSign);

/// The ring inserted into `mesh` (its vertices cells of a tile of `cellCount`) as constraints.
/// Throws Error where the ring crosses itself or a vertex lies on a side's chord (which the
/// choice of the sides' cells rules out).
ConstrainedTin constrainToRing(TinMesh mesh, const TileRing& ring, std::size_t cellCount);

} // namespace terratin::detail

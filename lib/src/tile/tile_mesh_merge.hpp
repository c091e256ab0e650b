#pragma once
/// @file
/// One TIN from the TINs of tiles that share their border vertices (issue 25's seam-free
/// tiles): a border vertex is one vertex, and two triangles of neighbouring tiles on the same
/// border edge become neighbours.

#include "terratin/triangulate/tin_mesh.hpp"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace terratin::detail {

class TileMeshMerger {
public:
    /// `gridWidth`: the whole grid's width in cells, which numbers the cells of the merged TIN.
    explicit TileMeshMerger(std::size_t gridWidth) : m_gridWidth(gridWidth) {}

    /// Adds a tile's TIN, whose sourceIndex numbers the cells of a window `tileWidth` cells
    /// wide starting at (firstRow, firstColumn) of the grid.
    void add(const TinMesh& tile, std::size_t tileWidth, std::size_t firstRow,
             std::size_t firstColumn);

    /// The merged TIN: vertices in cell order (sourceIndex = the grid's cell index), triangles
    /// tile after tile, each tile's in its own order; each edge on a shared border joins the
    /// two triangles on it. Throws Error when the tiles do not fit together: a cell with two
    /// positions, an edge with more than two triangles, or two on the same side of it.
    [[nodiscard]] TinMesh finish();

private:
    struct CellVertex {
        std::uint32_t cell;
        Point3 position;
    };
    /// A triangle edge with no neighbour in its own tile, to be matched across tiles.
    struct OpenEdge {
        std::uint64_t key; // the two corner cells, smaller first
        std::uint32_t triangle;
        std::uint8_t edge;
        bool forward; // whether the edge runs from the smaller cell to the larger
    };

    void joinOpenEdges(TinMesh& merged);

    std::size_t m_gridWidth;
    std::vector<CellVertex> m_vertices;
    /// Corner cells (the grid's cell indices), three per triangle; and neighbours, with
    /// kNoNeighbour where a border may hold one.
    std::vector<std::uint32_t> m_cornerCells;
    std::vector<std::int32_t> m_neighbours;
    std::vector<OpenEdge> m_openEdges;
};

} // namespace terratin::detail

#pragma once
/// @file
/// One TIN from the TINs of tiles that share their border vertices (seam-free tiles): a
/// border vertex is one vertex, and two triangles of neighbouring tiles on the same
/// border edge become neighbours.

#include "joined_vertex_numbers.hpp"
#include "tile_grid.hpp"

#include "terratin/triangulate/tin_mesh.hpp"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace terratin::detail {

class TileMeshMerger {
public:
    /// `gridWidth`: the whole grid's width in cells, which numbers the cells of the merged TIN.
    explicit TileMeshMerger(std::size_t gridWidth) : m_gridWidth(gridWidth), m_numbers(gridWidth) {}

    /// Adds a tile's TIN, whose sourceIndex numbers the cells of the tile at `place`. Its
    /// vertices follow those of the tiles added before, less the ones on its sides that a tile
    /// added before has already given; its triangles follow theirs.
    void add(const TinMesh& tile, const TilePlace& place);

    /// The merged TIN (sourceIndex = the grid's cell index), each edge on a shared side joining
    /// the two triangles on it. Throws Error when the tiles do not fit together: a cell with
    /// two positions, an edge with more than two triangles, or two on the same side of it.
    [[nodiscard]] TinMesh finish();

private:
    /// A triangle edge on a tile's side, to be matched across tiles.
    struct OpenEdge {
        std::uint64_t key; // the two vertices, smaller first
        std::uint32_t triangle;
        std::uint8_t edge;
        bool forward; // whether the edge runs from the smaller vertex to the larger
    };

    /// The merged vertex of the tile's vertex v.
    std::uint32_t vertexOf(const TinMesh& tile, std::uint32_t v, const TilePlace& place);
    void joinOpenEdges();

    std::size_t m_gridWidth;
    TinMesh m_merged;
    JoinedVertexNumbers m_numbers;
    std::vector<OpenEdge> m_openEdges;
};

} // namespace terratin::detail

#include "tile_mesh_merge.hpp"

#include "terratin/error.hpp"

#include <algorithm>
#include <limits>
#include <string>

namespace terratin::detail {

namespace {

std::uint64_t edgeKey(std::uint32_t a, std::uint32_t b) {
    const std::uint32_t low = std::min(a, b);
    const std::uint32_t high = std::max(a, b);
    return (std::uint64_t{low} << 32U) | high;
}

} // namespace

void TileMeshMerger::add(const TinMesh& tile, std::size_t tileWidth, std::size_t firstRow,
                         std::size_t firstColumn) {
    const auto gridCell = [&](std::uint32_t tileCell) {
        const std::size_t row = firstRow + tileCell / tileWidth;
        const std::size_t column = firstColumn + tileCell % tileWidth;
        return static_cast<std::uint32_t>(row * m_gridWidth + column);
    };
    for (std::size_t v = 0; v < tile.vertexCount(); ++v)
        m_vertices.push_back({gridCell(tile.sourceIndex[v]), tile.vertices[v]});

    const std::size_t base = m_cornerCells.size() / 3;
    if (base + tile.triangleCount() >
        static_cast<std::size_t>(std::numeric_limits<std::int32_t>::max()))
        throw Error("Tiles: more than 2^31 - 1 triangles in all");
    for (std::size_t t = 0; t < tile.triangleCount(); ++t)
        for (std::size_t e = 0; e < 3; ++e) {
            const std::size_t i = 3 * t + e;
            m_cornerCells.push_back(gridCell(tile.sourceIndex[tile.triangles[i]]));
            const std::int32_t n = tile.neighbours[i];
            m_neighbours.push_back(n == kNoNeighbour ? kNoNeighbour
                                                     : n + static_cast<std::int32_t>(base));
        }
    for (std::size_t t = base; t < m_cornerCells.size() / 3; ++t)
        for (std::uint8_t e = 0; e < 3; ++e) {
            if (m_neighbours[3 * t + e] != kNoNeighbour)
                continue;
            const std::uint32_t a = m_cornerCells[3 * t + e];
            const std::uint32_t b = m_cornerCells[3 * t + (e + 1U) % 3U];
            m_openEdges.push_back({edgeKey(a, b), static_cast<std::uint32_t>(t), e, a < b});
        }
}

TinMesh TileMeshMerger::finish() {
    std::sort(m_vertices.begin(), m_vertices.end(),
              [](const CellVertex& a, const CellVertex& b) { return a.cell < b.cell; });
    TinMesh merged;
    std::vector<std::uint32_t> cells;
    for (std::size_t i = 0; i < m_vertices.size(); ++i) {
        const CellVertex& vertex = m_vertices[i];
        if (!cells.empty() && cells.back() == vertex.cell) {
            const Point3& kept = merged.vertices[merged.vertices.size() - 1];
            if (!(kept == vertex.position))
                throw Error("Tiles: cell " + std::to_string(vertex.cell) +
                            " lies at two positions in two tiles");
            continue;
        }
        cells.push_back(vertex.cell);
        merged.vertices.push_back(vertex.position);
        merged.sourceIndex.push_back(vertex.cell);
    }
    m_vertices = {};

    merged.triangles.resize(m_cornerCells.size());
    for (std::size_t i = 0; i < m_cornerCells.size(); ++i)
        merged.triangles[i] = static_cast<std::uint32_t>(
            std::lower_bound(cells.begin(), cells.end(), m_cornerCells[i]) - cells.begin());
    merged.neighbours.resize(m_neighbours.size());
    std::copy(m_neighbours.begin(), m_neighbours.end(), merged.neighbours.begin());
    joinOpenEdges(merged);
    m_cornerCells = {};
    m_neighbours = {};
    return merged;
}

void TileMeshMerger::joinOpenEdges(TinMesh& merged) {
    std::sort(m_openEdges.begin(), m_openEdges.end(),
              [](const OpenEdge& a, const OpenEdge& b) { return a.key < b.key; });
    for (std::size_t i = 0; i < m_openEdges.size();) {
        std::size_t end = i + 1;
        while (end < m_openEdges.size() && m_openEdges[end].key == m_openEdges[i].key)
            ++end;
        if (end - i > 2 || (end - i == 2 && m_openEdges[i].forward == m_openEdges[i + 1].forward))
            throw Error("Tiles: the edge between cells " +
                        std::to_string(m_openEdges[i].key >> 32U) + " and " +
                        std::to_string(m_openEdges[i].key & 0xFFFFFFFFU) +
                        " has triangles of two tiles on one side");
        if (end - i == 2) {
            const OpenEdge& a = m_openEdges[i];
            const OpenEdge& b = m_openEdges[i + 1];
            merged.neighbours[3 * std::size_t{a.triangle} + a.edge] =
                static_cast<std::int32_t>(b.triangle);
            merged.neighbours[3 * std::size_t{b.triangle} + b.edge] =
                static_cast<std::int32_t>(a.triangle);
        }
        i = end;
    }
    m_openEdges = {};
}

} // namespace terratin::detail

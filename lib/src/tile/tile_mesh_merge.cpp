#include "tile_mesh_merge.hpp"

#include "terratin/error.hpp"

#include <algorithm>
#include <limits>
#include <string>

namespace terratin::detail {

namespace {

std::uint64_t edgeKey(std::uint32_t a, std::uint32_t b) {
    return (std::uint64_t{std::min(a, b)} << 32U) | std::max(a, b);
}

} // namespace

std::uint32_t TileMeshMerger::vertexOf(const TinMesh& tile, std::uint32_t v,
                                       const TilePlace& place) {
    const std::size_t row = tile.sourceIndex[v] / place.width;
    const std::size_t column = tile.sourceIndex[v] % place.width;
    const auto cell = static_cast<std::uint32_t>((place.firstRow + row) * m_gridWidth +
                                                 place.firstColumn + column);
    const JoinedVertexNumbers::Number number = m_numbers.number(cell, place);
    if (!number.isNew) {
        if (!(m_merged.vertices[number.number] == tile.vertices[v]))
            throw Error("Tiles: cell " + std::to_string(cell) +
                        " lies at two positions in two tiles");
        return number.number;
    }
    m_merged.vertices.push_back(tile.vertices[v]);
    m_merged.sourceIndex.push_back(cell);
    return number.number;
}

void TileMeshMerger::add(const TinMesh& tile, const TilePlace& place) {
    std::vector<std::uint32_t> merged(tile.vertexCount());
    for (std::size_t v = 0; v < tile.vertexCount(); ++v)
        merged[v] = vertexOf(tile, static_cast<std::uint32_t>(v), place);

    const std::size_t base = m_merged.triangleCount();
    if (base + tile.triangleCount() >
        static_cast<std::size_t>(std::numeric_limits<std::int32_t>::max()))
        throw Error("Tiles: more than 2^31 - 1 triangles in all");
    for (std::size_t i = 0; i < tile.triangles.size(); ++i) {
        m_merged.triangles.push_back(merged[tile.triangles[i]]);
        const std::int32_t n = tile.neighbours[i];
        m_merged.neighbours.push_back(n == kNoNeighbour ? kNoNeighbour
                                                        : n + static_cast<std::int32_t>(base));
    }
    for (std::size_t t = base; t < m_merged.triangleCount(); ++t)
        for (std::uint8_t e = 0; e < 3; ++e) {
            if (m_merged.neighbours[3 * t + e] != kNoNeighbour)
                continue;
            const std::uint32_t a = m_merged.triangles[3 * t + e];
            const std::uint32_t b = m_merged.triangles[3 * t + (e + 1U) % 3U];
            m_openEdges.push_back({edgeKey(a, b), static_cast<std::uint32_t>(t), e, a < b});
        }
}

TinMesh TileMeshMerger::finish() {
    joinOpenEdges();
    m_numbers = JoinedVertexNumbers(m_gridWidth);
    return std::move(m_merged);
}

void TileMeshMerger::joinOpenEdges() {
    std::sort(m_openEdges.begin(), m_openEdges.end(),
              [](const OpenEdge& a, const OpenEdge& b) { return a.key < b.key; });
    for (std::size_t i = 0; i < m_openEdges.size();) {
        std::size_t end = i + 1;
        while (end < m_openEdges.size() && m_openEdges[end].key == m_openEdges[i].key)
            ++end;
        if (end - i > 2 || (end - i == 2 && m_openEdges[i].forward == m_openEdges[i + 1].forward))
            throw Error("Tiles: the edge between vertices " +
                        std::to_string(m_openEdges[i].key >> 32U) + " and " +
                        std::to_string(m_openEdges[i].key & 0xFFFFFFFFU) +
                        " has triangles of two tiles on one side");
        if (end - i == 2) {
            const OpenEdge& a = m_openEdges[i];
            const OpenEdge& b = m_openEdges[i + 1];
            m_merged.neighbours[3 * std::size_t{a.triangle} + a.edge] =
                static_cast<std::int32_t>(b.triangle);
            m_merged.neighbours[3 * std::size_t{b.triangle} + b.edge] =
                static_cast<std::int32_t>(a.triangle);
        }
        i = end;
    }
    m_openEdges = {};
}

} // namespace terratin::detail

#include "tile_ring.hpp"

#include "terratin/constrain/insert_constraints.hpp"
#include "terratin/error.hpp"

#include <algorithm>
#include <limits>
#include <utility>

namespace terratin::detail {

namespace {

constexpr std::uint32_t kNotAVertex = std::numeric_limits<std::uint32_t>::max();

std::uint64_t edgeKey(std::uint32_t from, std::uint32_t to) {
    return (std::uint64_t{from} << 32U) | to;
}

/// The ring's edges in `tin` (its chains, which the cells inserted on them split), as sorted
/// keys directed with the tile on their left at the positions (where the pixel frame's ring has
/// it when `frameSign` is +1).
std::vector<std::uint64_t> ringEdges(const ConstrainedTin& tin, int frameSign) {
    std::vector<std::uint64_t> edges;
    for (const std::vector<std::uint32_t>& chain : tin.chains)
        for (std::size_t i = 0; i + 1 < chain.size(); ++i)
            edges.push_back(frameSign > 0 ? edgeKey(chain[i], chain[i + 1])
                                          : edgeKey(chain[i + 1], chain[i]));
    std::sort(edges.begin(), edges.end());
    return edges;
}

} // namespace

TileRing::TileRing(const PlacedTile& tile, const std::vector<std::vector<std::uint32_t>>& kept)
    : m_tile(&tile), m_width(tile.width()), m_height(tile.height()) {
    std::vector<std::uint32_t> order = kept[0];
    order.insert(order.end(), kept[3].begin(), kept[3].end());
    order.insert(order.end(), kept[1].rbegin(), kept[1].rend());
    order.insert(order.end(), kept[2].rbegin(), kept[2].rend());
    order.erase(std::unique(order.begin(), order.end()), order.end());
    if (order.size() > 1 && order.front() == order.back())
        order.pop_back();
    for (std::size_t c = 0; c < tile.at.size(); ++c)
        if (tile.read.grid.isValid(c) && !onSide(static_cast<std::uint32_t>(c)))
            m_interior.push_back(static_cast<std::uint32_t>(c));
    if (order.size() < 2)
        startFromTwo(order);
    for (std::size_t k = 0; k < order.size(); ++k) {
        const std::uint32_t u = order[k];
        const std::uint32_t v = order[(k + 1) % order.size()];
        m_cells.push_back(u);
        m_alongSide.push_back(alongOneSide(u, v));
        if (!m_alongSide.back())
            chainBetween(u, v, outsideOf(u, v, m_interior));
    }
}

bool TileRing::alongOneSide(std::uint32_t u, std::uint32_t v) const {
    const std::size_t ur = u / m_width;
    const std::size_t uc = u % m_width;
    const std::size_t vr = v / m_width;
    const std::size_t vc = v % m_width;
    return (ur == 0 && vr == 0 && vc > uc) || (uc + 1 == m_width && vc + 1 == m_width && vr > ur) ||
           (ur + 1 == m_height && vr + 1 == m_height && vc < uc) || (uc == 0 && vc == 0 && vr < ur);
}

std::vector<std::uint32_t> TileRing::outsideOf(std::uint32_t u, std::uint32_t v,
                                               const std::vector<std::uint32_t>& cells) const {
    std::vector<std::uint32_t> outside;
    for (const std::uint32_t c : cells)
        if (c != u && c != v && inward(u, v, c) < 0.0)
            outside.push_back(c);
    return outside;
}

void TileRing::chainBetween(std::uint32_t u, std::uint32_t v,
                            const std::vector<std::uint32_t>& outside) {
    if (outside.empty())
        return;
    std::uint32_t farthest = outside.front();
    double farthestDistance = 0.0;
    for (const std::uint32_t c : outside) {
        const double distance = -inward(u, v, c);
        if (distance > farthestDistance) {
            farthest = c;
            farthestDistance = distance;
        }
    }
    const std::vector<std::uint32_t> before = outsideOf(u, farthest, outside);
    const std::vector<std::uint32_t> after = outsideOf(farthest, v, outside);
    chainBetween(u, farthest, before);
    m_cells.push_back(farthest);
    m_alongSide.push_back(0);
    chainBetween(farthest, v, after);
}

void TileRing::startFromTwo(std::vector<std::uint32_t>& order) const {
    if (order.empty() && !m_interior.empty())
        order.push_back(m_interior.front());
    if (order.empty())
        return;
    const Point2 first = m_tile->at[order.front()];
    std::uint32_t farthest = order.front();
    double farthestDistance = 0.0;
    for (const std::uint32_t c : m_interior) {
        const double dx = m_tile->at[c].x - first.x;
        const double dy = m_tile->at[c].y - first.y;
        if (dx * dx + dy * dy > farthestDistance) {
            farthest = c;
            farthestDistance = dx * dx + dy * dy;
        }
    }
    if (farthest != order.front())
        order.push_back(farthest);
}

std::vector<std::uint8_t> sideCellsInside(const TileRing& ring, const HeightGrid& grid) {
    std::vector<std::uint8_t> inside(grid.cellCount(), 0);
    const std::vector<std::uint32_t>& cells = ring.cells();
    const auto width = static_cast<std::uint32_t>(grid.width);
    for (std::size_t k = 0; k < cells.size(); ++k) {
        if (!ring.alongSide(k))
            continue;
        const std::uint32_t u = cells[k];
        const std::uint32_t v = cells[(k + 1) % cells.size()];
        const bool alongRow = u / width == v / width;
        const std::uint32_t step = alongRow ? 1 : width;
        for (std::uint32_t c = std::min(u, v) + step; c < std::max(u, v); c += step)
            if (grid.isValid(c) && ring.inward(u, v, c) > 0.0)
                inside[c] = 1;
    }
    return inside;
}

std::vector<std::uint8_t> trianglesOutsideRing(const ConstrainedTin& tin, int frameSign) {
    const std::vector<std::uint64_t> ring = ringEdges(tin, frameSign);
    const TinMesh& mesh = tin.mesh;
    std::vector<std::uint8_t> outside(mesh.triangleCount(), 0);
    std::vector<std::size_t> pending;
    for (std::size_t t = 0; t < mesh.triangleCount(); ++t)
        for (std::size_t e = 0; e < 3; ++e) {
            const std::uint32_t a = mesh.triangles[3 * t + e];
            const std::uint32_t b = mesh.triangles[3 * t + (e + 1) % 3];
            // A counter-clockwise triangle lies on the left of its edge a -> b, so on the right
            // of the ring edge b -> a.
            if (tin.constrained[3 * t + e] != 0 && outside[t] == 0 &&
                std::binary_search(ring.begin(), ring.end(), edgeKey(b, a))) {
                outside[t] = 1;
                pending.push_back(t);
            }
        }
    while (!pending.empty()) {
        const std::size_t t = pending.back();
        pending.pop_back();
        for (std::size_t e = 0; e < 3; ++e) {
            const std::int32_t n = mesh.neighbours[3 * t + e];
            if (n == kNoNeighbour || tin.constrained[3 * t + e] != 0 ||
                outside[static_cast<std::size_t>(n)] != 0)
                continue;
            outside[static_cast<std::size_t>(n)] = 1;
            pending.push_back(static_cast<std::size_t>(n));
        }
    }
    return outside;
}

ConstrainedTin constrainToRing(TinMesh mesh, const TileRing& ring, std::size_t cellCount) {
    std::vector<std::uint32_t> vertexOfCell(cellCount, kNotAVertex);
    for (std::uint32_t v = 0; v < mesh.vertexCount(); ++v) {
        const std::uint32_t cell = mesh.sourceIndex[v];
        if (cell >= cellCount)
            throw Error("Tiles: a vertex of a tile's TIN is no cell of the tile");
        vertexOfCell[cell] = v;
    }
    const std::vector<std::uint32_t>& cells = ring.cells();
    ConstraintSet set;
    for (std::size_t k = 0; k < cells.size(); ++k) {
        const std::uint32_t u = cells[k];
        const std::uint32_t v = cells[(k + 1) % cells.size()];
        if (vertexOfCell[u] == kNotAVertex || vertexOfCell[v] == kNotAVertex)
            throw Error("Tiles: a cell of a tile's boundary is no vertex of its TIN");
        set.segments.push_back({vertexOfCell[u], vertexOfCell[v]});
    }
    ConstrainedTin tin = insertConstraints(std::move(mesh), set);
    if (tin.intersections > 0 || tin.addedPoints > 0)
        throw Error("Tiles: a tile's boundary crosses itself");
    for (std::size_t k = 0; k < tin.chains.size(); ++k)
        if (ring.alongSide(k) && tin.chains[k].size() != 2)
            throw Error("Tiles: a vertex lies on the chord between two side cells of a tile");
    return tin;
}

} // namespace terratin::detail

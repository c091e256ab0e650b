#include "vertex_buckets.hpp"

#include <algorithm>
#include <cmath>

namespace terratin::detail {

VertexBuckets::VertexBuckets(const MeshArray<Point3>& vertices) {
    Point2 max{vertices.front().x, vertices.front().y};
    m_min = max;
    for (const Point3& p : vertices) {
        m_min = {std::min(m_min.x, p.x), std::min(m_min.y, p.y)};
        max = {std::max(max.x, p.x), std::max(max.y, p.y)};
    }
    m_side = std::max<std::size_t>(
        1, static_cast<std::size_t>(std::sqrt(static_cast<double>(vertices.size()) /
                                              static_cast<double>(kVerticesPerBucket))));
    const auto side = static_cast<double>(m_side);
    m_cellsPerUnitX = max.x > m_min.x ? side / (max.x - m_min.x) : 0.0;
    m_cellsPerUnitY = max.y > m_min.y ? side / (max.y - m_min.y) : 0.0;
    m_first.assign(m_side * m_side, kEmpty);
    for (std::size_t v = 0; v < vertices.size(); ++v) {
        std::uint32_t& first = m_first[row(vertices[v].y) * m_side + column(vertices[v].x)];
        if (first == kEmpty)
            first = static_cast<std::uint32_t>(v);
    }
}

// Rounding only moves a point to a neighbouring bucket: the result is a starting place.
std::size_t VertexBuckets::column(double x) const {
    const double cell = (x - m_min.x) * m_cellsPerUnitX;
    return cell <= 0.0 ? 0 : std::min(m_side - 1, static_cast<std::size_t>(cell));
}

std::size_t VertexBuckets::row(double y) const {
    const double cell = (y - m_min.y) * m_cellsPerUnitY;
    return cell <= 0.0 ? 0 : std::min(m_side - 1, static_cast<std::size_t>(cell));
}

std::uint32_t VertexBuckets::vertexNear(const Point2& p) const {
    const auto centreColumn = static_cast<std::ptrdiff_t>(column(p.x));
    const auto centreRow = static_cast<std::ptrdiff_t>(row(p.y));
    const auto side = static_cast<std::ptrdiff_t>(m_side);
    for (std::ptrdiff_t ring = 0; ring < side; ++ring)
        for (std::ptrdiff_t r = centreRow - ring; r <= centreRow + ring; ++r)
            for (std::ptrdiff_t c = centreColumn - ring; c <= centreColumn + ring; ++c) {
                const bool onRing = r == centreRow - ring || r == centreRow + ring ||
                                    c == centreColumn - ring || c == centreColumn + ring;
                if (!onRing || r < 0 || c < 0 || r >= side || c >= side)
                    continue;
                const std::uint32_t v = m_first[static_cast<std::size_t>(r * side + c)];
                if (v != kEmpty)
                    return v;
            }
    return 0;
}

} // namespace terratin::detail

#include "cell_in_triangle.hpp"

#include "terratin/geometry/predicates.hpp"

#include <cmath>

namespace terratin::detail {

bool onEdgeLine(const TinMesh& mesh, std::size_t t, std::size_t i, Point2 p) {
    const Point3& a = mesh.vertices[mesh.triangles[3 * t + i]];
    const Point3& b = mesh.vertices[mesh.triangles[3 * t + (i + 1) % 3]];
    const double detLeft = (a.x - p.x) * (b.y - p.y);
    const double detRight = (a.y - p.y) * (b.x - p.x);
    return std::fabs(detLeft - detRight) <=
           predicates::detail::kOrient2dErrorBoundA * (std::fabs(detLeft) + std::fabs(detRight));
}

std::int32_t neighbourSharing(const TinMesh& mesh, std::size_t t, Point2 p) {
    for (std::size_t i = 0; i < 3; ++i)
        if (onEdgeLine(mesh, t, i, p))
            return mesh.neighbours[3 * t + i];
    return kNoNeighbour;
}

std::int32_t keptTriangleAt(const TinMesh& mesh, std::size_t t, Point2 p,
                            std::span<const std::uint8_t> left) {
    const auto kept = [&](std::size_t u) { return left[u] == 0; };
    const std::size_t corner = cornerAt(mesh, t, p);
    if (corner == 3) {
        for (std::size_t i = 0; i < 3; ++i) {
            const std::int32_t n = mesh.neighbours[3 * t + i];
            if (n != kNoNeighbour && kept(static_cast<std::size_t>(n)) && onEdgeLine(mesh, t, i, p))
                return n;
        }
        return kNoNeighbour;
    }
    // Around the vertex, one way and then the other, until a kept triangle or the hull.
    const std::uint32_t vertex = mesh.triangles[3 * t + corner];
    for (const std::size_t turn : {std::size_t{0}, std::size_t{2}}) {
        std::int32_t u = static_cast<std::int32_t>(t);
        for (;;) {
            const auto at = static_cast<std::size_t>(u);
            std::size_t i = 0;
            while (mesh.triangles[3 * at + i] != vertex)
                ++i;
            u = mesh.neighbours[3 * at + (i + turn) % 3];
            if (u == kNoNeighbour || u == static_cast<std::int32_t>(t))
                break;
            if (kept(static_cast<std::size_t>(u)))
                return u;
        }
    }
    return kNoNeighbour;
}

} // namespace terratin::detail

#pragma once
/// @file
/// Where a cell's position lies on a triangle of a TinMesh that holds it: at a corner, on an
/// edge's line, and the elevation of the triangle's plane there. The completion of a
/// constrained TIN (cell_completion.hpp) measures each cell in the triangle a walk found, and
/// moves a cell on an edge or at a vertex into a kept triangle beside it.

#include "terratin/geometry/point.hpp"
#include "terratin/triangulate/tin_mesh.hpp"

#include <cstddef>
#include <cstdint>
#include <span>

namespace terratin::detail {

/// Whether p lies on the line of edge i of triangle t, up to rounding (within the error bound
/// of orient2d's floating-point stage, as TinLocator::locateNear decides).
bool onEdgeLine(const TinMesh& mesh, std::size_t t, std::size_t i, Point2 p);

/// The triangle across the edge of triangle t that p lies on, or kNoNeighbour when p lies on
/// none or that edge is on the hull. The first such edge.
std::int32_t neighbourSharing(const TinMesh& mesh, std::size_t t, Point2 p);

/// The corner of triangle t at p (0 to 2), or 3 when none is.
inline std::size_t cornerAt(const TinMesh& mesh, std::size_t t, Point2 p) {
    for (std::size_t i = 0; i < 3; ++i) {
        const Point3& corner = mesh.vertices[mesh.triangles[3 * t + i]];
        if (corner.x == p.x && corner.y == p.y)
            return i;
    }
    return 3;
}

/// Whether p is a corner of triangle t.
inline bool isCorner(const TinMesh& mesh, std::size_t t, Point2 p) {
    return cornerAt(mesh, t, p) < 3;
}

/// A kept triangle (left[u] == 0) that holds p on its boundary, found from triangle t (which
/// holds p): around p's vertex when p is a corner of t, else across an edge p lies on;
/// kNoNeighbour when none does. Slivers whose corners all lie near one line (a constrained
/// boundary's pockets) hold p near several edges' lines: every such edge is tried.
std::int32_t keptTriangleAt(const TinMesh& mesh, std::size_t t, Point2 p,
                            std::span<const std::uint8_t> left);

/// The plane of triangle t at p (barycentric, in double).
inline double planeAt(const TinMesh& mesh, std::size_t t, Point2 p) {
    const Point3& a = mesh.vertices[mesh.triangles[3 * t]];
    const Point3& b = mesh.vertices[mesh.triangles[3 * t + 1]];
    const Point3& c = mesh.vertices[mesh.triangles[3 * t + 2]];
    const double area = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
    const double wb = ((p.x - a.x) * (c.y - a.y) - (p.y - a.y) * (c.x - a.x)) / area;
    const double wc = ((b.x - a.x) * (p.y - a.y) - (b.y - a.y) * (p.x - a.x)) / area;
    return a.z + wb * (b.z - a.z) + wc * (c.z - a.z);
}

} // namespace terratin::detail

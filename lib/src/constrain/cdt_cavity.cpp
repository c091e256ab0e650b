// CdtMesh::replaceCavity: the one write of a segment's retriangulated region
// (segment_cavity.hpp), beside cdt_flips.cpp's flips and splits.

#include "cdt_mesh.hpp"

#include <stdexcept>

namespace terratin::detail {

void CdtMesh::replaceCavity(std::span<const std::size_t> slots,
                            std::span<const std::size_t> boundary,
                            std::span<const CavityTriangle> triangles) {
    if (slots.size() != triangles.size() || boundary.size() != triangles.size() + 2)
        throw std::logic_error("CdtMesh: a cavity refilled with another number of triangles");
    m_cavityBoundary.clear();
    for (const std::size_t h : boundary)
        m_cavityBoundary.push_back(
            {from(h), to(h), m_arrays->mesh.neighbours[h], m_arrays->constrained[h]});
    std::size_t boundaryEdges = 0;
    for (const CavityTriangle& triangle : triangles)
        for (std::size_t i = 0; i < 3; ++i) {
            if ((triangle.across[i] & CavityTriangle::kCavityBoundary) == 0)
                continue;
            const std::size_t k = triangle.across[i] & ~CavityTriangle::kCavityBoundary;
            if (k >= boundary.size() || m_cavityBoundary[k].from != triangle.corners[i] ||
                m_cavityBoundary[k].to != triangle.corners[(i + 1) % 3])
                throw std::logic_error("CdtMesh: a cavity's new edge is not the boundary's");
            ++boundaryEdges;
        }
    if (boundaryEdges != boundary.size())
        throw std::logic_error("CdtMesh: a cavity's new triangles leave its boundary open");

    for (std::size_t k = 0; k < triangles.size(); ++k) {
        const CavityTriangle& triangle = triangles[k];
        const std::size_t t = slots[k];
        writeCorners(t, triangle.corners[0], triangle.corners[1], triangle.corners[2]);
        for (std::size_t i = 0; i < 3; ++i) {
            const std::size_t h = 3 * t + i;
            if ((triangle.across[i] & CavityTriangle::kCavityBoundary) == 0) {
                m_arrays->mesh.neighbours[h] = static_cast<std::int32_t>(slots[triangle.across[i]]);
                m_arrays->constrained[h] = 0;
                continue;
            }
            const BoundaryEdge& edge =
                m_cavityBoundary[triangle.across[i] & ~CavityTriangle::kCavityBoundary];
            m_arrays->mesh.neighbours[h] = edge.outer;
            m_arrays->constrained[h] = edge.flag;
            relink(edge.outer, edge.to, t);
        }
    }
}

} // namespace terratin::detail

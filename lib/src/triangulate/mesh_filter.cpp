#include "terratin/triangulate/mesh_filter.hpp"

#include "terratin/error.hpp"

#include <cmath>
#include <limits>
#include <string>
#include <vector>

namespace terratin {

std::size_t dropTriangles(TinMesh& mesh, std::span<const std::uint8_t> drop) {
    const std::size_t triangleCount = mesh.triangleCount();
    if (drop.size() != triangleCount)
        throw Error("MeshFilter: " + std::to_string(drop.size()) + " flags for " +
                    std::to_string(triangleCount) + " triangles");
    // New numbers of the kept triangles, then of the vertices they use.
    std::vector<std::int32_t> newTriangle(triangleCount, kNoNeighbour);
    std::size_t kept = 0;
    for (std::size_t t = 0; t < triangleCount; ++t)
        if (drop[t] == 0)
            newTriangle[t] = static_cast<std::int32_t>(kept++);
    if (kept == triangleCount)
        return 0;
    constexpr std::uint32_t kUnused = std::numeric_limits<std::uint32_t>::max();
    std::vector<std::uint32_t> newVertex(mesh.vertexCount(), kUnused);
    for (std::size_t t = 0; t < triangleCount; ++t)
        if (drop[t] == 0)
            for (int i = 0; i < 3; ++i)
                newVertex[mesh.triangles[3 * t + i]] = 0;
    std::uint32_t vertices = 0;
    for (std::size_t v = 0; v < newVertex.size(); ++v) {
        if (newVertex[v] == kUnused)
            continue;
        newVertex[v] = vertices;
        mesh.vertices[vertices] = mesh.vertices[v];
        if (!mesh.sourceIndex.empty())
            mesh.sourceIndex[vertices] = mesh.sourceIndex[v];
        ++vertices;
    }
    mesh.vertices.resize(vertices);
    if (!mesh.sourceIndex.empty())
        mesh.sourceIndex.resize(vertices);

    // Compact in place: triangle t moves to newTriangle[t] <= t.
    for (std::size_t t = 0; t < triangleCount; ++t) {
        if (drop[t] != 0)
            continue;
        const auto to = static_cast<std::size_t>(newTriangle[t]);
        for (int i = 0; i < 3; ++i) {
            const std::int32_t across = mesh.neighbours[3 * t + i];
            mesh.triangles[3 * to + i] = newVertex[mesh.triangles[3 * t + i]];
            mesh.neighbours[3 * to + i] = across == kNoNeighbour
                                              ? kNoNeighbour
                                              : newTriangle[static_cast<std::size_t>(across)];
        }
    }
    mesh.triangles.resize(3 * kept);
    mesh.neighbours.resize(3 * kept);
    return triangleCount - kept;
}

std::vector<std::uint8_t> longEdgeTriangles(const TinMesh& mesh, double maxEdge) {
    if (!(maxEdge > 0.0) || !std::isfinite(maxEdge))
        throw InvalidInputError("MeshFilter: the maximum edge length must be positive and finite");
    const double maxSquared = maxEdge * maxEdge;
    std::vector<std::uint8_t> drop(mesh.triangleCount(), 0);
    for (std::size_t t = 0; t < drop.size(); ++t) {
        for (int i = 0; i < 3; ++i) {
            const Point3& a = mesh.vertices[mesh.triangles[3 * t + i]];
            const Point3& b = mesh.vertices[mesh.triangles[3 * t + (i + 1) % 3]];
            const double dx = b.x - a.x;
            const double dy = b.y - a.y;
            if (dx * dx + dy * dy > maxSquared)
                drop[t] = 1;
        }
    }
    return drop;
}

std::size_t dropLongEdgeTriangles(TinMesh& mesh, double maxEdge) {
    return dropTriangles(mesh, longEdgeTriangles(mesh, maxEdge));
}

} // namespace terratin

#include "cdt_mesh.hpp"
#include "terratin/constrain/insert_constraints.hpp"
#include "terratin/error.hpp"
#include "zoned_vertices.hpp"

#include <algorithm>
#include <cmath>
#include <string>

namespace terratin {

namespace {

/// Puts `middle` between consecutive vertices a and b (either order) of every chain holding
/// them. Splits of constrained edges are rare, so the chains are searched.
void insertIntoChains(std::vector<std::vector<std::uint32_t>>& chains, std::uint32_t a,
                      std::uint32_t b, std::uint32_t middle) {
    for (std::vector<std::uint32_t>& chain : chains)
        for (std::size_t j = 1; j < chain.size(); ++j)
            if ((chain[j - 1] == a && chain[j] == b) || (chain[j - 1] == b && chain[j] == a)) {
                chain.insert(chain.begin() + static_cast<std::ptrdiff_t>(j), middle);
                ++j;
            }
}

/// Inserts points[i] for each i of `order` on this thread, each walk starting at near[i]
/// when given, else where the previous one ended. Returns the number inserted.
std::size_t insertInOrder(detail::CdtMesh& mesh, ConstrainedTin& tin,
                          std::span<const Point3> points, std::span<const std::uint32_t> sources,
                          std::span<const std::uint32_t> near, std::span<const std::size_t> order) {
    std::size_t inserted = 0;
    std::size_t hint = 0;
    for (const std::size_t i : order) {
        const Point3& p = points[i];
        const detail::MeshLocation where = mesh.locate({p.x, p.y}, near.empty() ? hint : near[i]);
        if (where.kind == detail::MeshLocation::Kind::OutsideHull)
            throw InvalidInputError("insertVertices: point " + std::to_string(i) +
                                    " lies outside the convex hull of the mesh");
        hint = where.halfEdge / 3;
        if (where.kind == detail::MeshLocation::Kind::OnVertex)
            continue;
        const std::uint32_t v = mesh.insertPoint(
            p, sources[i], where, [&](std::uint32_t a, std::uint32_t b, std::uint32_t middle) {
                insertIntoChains(tin.chains, a, b, middle);
            });
        hint = mesh.halfEdgeLeaving(v) / 3;
        ++inserted;
    }
    return inserted;
}

void checkInputs(const ConstrainedTin& tin, std::span<const Point3> points,
                 std::span<const std::uint32_t> sources, std::span<const std::uint32_t> near) {
    if (points.size() != sources.size() || (!near.empty() && near.size() != points.size()))
        throw InvalidInputError("insertVertices: " + std::to_string(points.size()) + " points, " +
                                std::to_string(sources.size()) + " sources and " +
                                std::to_string(near.size()) + " triangles to start from");
    const std::size_t triangles = tin.mesh.triangleCount();
    for (const std::uint32_t t : near)
        if (t >= triangles)
            throw InvalidInputError("insertVertices: triangle " + std::to_string(t) +
                                    " to start from is not one of the " +
                                    std::to_string(triangles));
    for (std::size_t i = 0; i < points.size(); ++i)
        if (!std::isfinite(points[i].x) || !std::isfinite(points[i].y) ||
            !std::isfinite(points[i].z))
            throw InvalidInputError("insertVertices: point " + std::to_string(i) +
                                    " is not finite");
}

/// The points in bands on the threads, then those they refused on this one, then the bands'
/// unused slots closed up (the chains follow the vertices moved).
std::size_t insertInZones(detail::CdtMesh& mesh, ConstrainedTin& tin,
                          std::span<const Point3> points, std::span<const std::uint32_t> sources,
                          std::span<const std::uint32_t> near, unsigned zones, unsigned threads,
                          std::vector<std::uint8_t>* changedTriangles) {
    const detail::ZonedVertices zoned = detail::insertVerticesInZones(
        mesh, points, sources, near, zones, threads, changedTriangles);
    const auto closeUp = [&] {
        const std::vector<std::uint32_t> movedTo =
            mesh.compact(zoned.unusedVertices, zoned.unusedTriangles);
        detail::renumberMoved(tin.chains, mesh.vertexCount(), movedTo);
    };
    std::size_t inserted = zoned.inserted;
    try {
        inserted += insertInOrder(mesh, tin, points, sources, near, zoned.refused);
    } catch (...) {
        closeUp(); // a point outside the hull: the TIN stays whole
        throw;
    }
    closeUp();
    return inserted;
}

} // namespace

std::size_t insertVertices(ConstrainedTin& tin, std::span<const Point3> points,
                           std::span<const std::uint32_t> sources,
                           std::vector<std::uint8_t>* changedTriangles,
                           std::span<const std::uint32_t> near, unsigned threads) {
    checkInputs(tin, points, sources, near);
    if (changedTriangles != nullptr)
        changedTriangles->assign(tin.mesh.triangleCount(), 0);
    if (points.empty())
        return 0;
    detail::CdtMesh mesh(std::move(tin.mesh), std::move(tin.constrained));
    mesh.recordWrites(changedTriangles);
    // Bands need each point's first triangle: without one, a point's walk starts where the
    // previous one ended.
    const unsigned zones = near.empty() ? 1 : detail::vertexZoneCount(points.size());
    std::size_t inserted = 0;
    try {
        if (zones > 1) {
            inserted =
                insertInZones(mesh, tin, points, sources, near, zones, threads, changedTriangles);
        } else {
            std::vector<std::size_t> order(points.size());
            for (std::size_t i = 0; i < order.size(); ++i)
                order[i] = i;
            inserted = insertInOrder(mesh, tin, points, sources, near, order);
        }
    } catch (...) {
        tin.constrained = mesh.takeFlags();
        tin.mesh = mesh.takeMesh();
        throw;
    }
    tin.constrained = mesh.takeFlags();
    tin.mesh = mesh.takeMesh();
    if (changedTriangles != nullptr)
        changedTriangles->resize(tin.mesh.triangleCount(), 0);
    return inserted;
}

} // namespace terratin

#include "zoned_vertices.hpp"

#include "../parallel/parallel_for.hpp"

#include <algorithm>
#include <bit>
#include <memory>

namespace terratin::detail {

namespace {

/// One band: its points, in order, and its view of the mesh.
struct VertexZone {
    Zone zone;
    std::vector<std::size_t> points;
    std::unique_ptr<CdtMesh> view;
    std::vector<std::size_t> refused;
    std::size_t inserted = 0;
};

/// `zones` bands of x holding about as many of `points` each; a point goes to its band's
/// points, or to its refused ones when its walk's first triangle has no corner in the band
/// (the band's view may not read it). Decided before any view works: the triangles are as
/// `near` found them.
std::vector<VertexZone> vertexBands(const CdtMesh& mesh, std::span<const Point3> points,
                                    std::span<const std::uint32_t> near, unsigned zones) {
    std::vector<double> xs;
    for (const Point3& p : points)
        xs.push_back(p.x);
    std::vector<VertexZone> bands(zones);
    const std::vector<Zone> bandZones = bandsHoldingAsMany(std::move(xs), zones, false);
    for (unsigned z = 0; z < zones; ++z)
        bands[z].zone = bandZones[z];
    for (std::size_t i = 0; i < points.size(); ++i) {
        VertexZone& band = *std::find_if(bands.begin(), bands.end(), [&](const VertexZone& b) {
            return points[i].x < b.zone.high;
        });
        const std::size_t t = near[i];
        const bool readable = band.zone.holds(mesh.vertex(mesh.from(3 * t))) ||
                              band.zone.holds(mesh.vertex(mesh.from(3 * t + 1))) ||
                              band.zone.holds(mesh.vertex(mesh.from(3 * t + 2)));
        (readable ? band.points : band.refused).push_back(i);
    }
    return bands;
}

/// Inserts a band's points through its view, refusing what the view may not do.
void runBand(VertexZone& band, std::span<const Point3> points,
             std::span<const std::uint32_t> sources, std::span<const std::uint32_t> near) {
    CdtMesh& view = *band.view;
    for (const std::size_t i : band.points) {
        const Point3& p = points[i];
        try {
            const MeshLocation where = view.locate({p.x, p.y}, near[i]);
            if (where.kind == MeshLocation::Kind::OnVertex)
                continue;
            // Outside the hull: the one-thread pass says so. On a constrained edge: the
            // chains through it are every band's.
            if (where.kind == MeshLocation::Kind::OutsideHull ||
                (where.kind == MeshLocation::Kind::OnEdge && view.isConstrained(where.halfEdge)))
                throw ZoneRefusal{};
            (void)view.insertPoint(p, sources[i], where,
                                   [](std::uint32_t, std::uint32_t, std::uint32_t) {});
            ++band.inserted;
        } catch (const ZoneRefusal&) {
            band.refused.push_back(i);
        }
    }
}

} // namespace

unsigned vertexZoneCount(std::size_t points) {
    return static_cast<unsigned>(
        std::clamp<std::size_t>(std::bit_floor(points / kPointsPerVertexZone), 1, kMaxVertexZones));
}

ZonedVertices insertVerticesInZones(CdtMesh& mesh, std::span<const Point3> points,
                                    std::span<const std::uint32_t> sources,
                                    std::span<const std::uint32_t> near, unsigned zones,
                                    unsigned threads, std::vector<std::uint8_t>* written) {
    std::vector<VertexZone> bands = vertexBands(mesh, points, near, zones);
    for (VertexZone& band : bands) {
        // A point makes one vertex and two triangles.
        const auto [vertexSlots, triangleSlots] =
            mesh.appendSlots(band.points.size(), 2 * band.points.size());
        band.view = std::make_unique<CdtMesh>(mesh, band.zone, vertexSlots, triangleSlots);
    }
    if (written != nullptr) // sized before the views write into it
        written->resize(mesh.mesh().triangleCount(), 0);
    for (VertexZone& band : bands)
        band.view->recordWrites(written);
    mesh.recordWrites(written);
    const unsigned workers = std::clamp(threads, 1U, zones);
    runOnThreads(workers, [&](unsigned worker) {
        for (std::size_t z = worker; z < bands.size(); z += workers)
            runBand(bands[z], points, sources, near);
    });

    ZonedVertices result;
    for (VertexZone& band : bands) {
        mesh.makePendingFlips(*band.view);
        result.inserted += band.inserted;
        result.unusedVertices.push_back(band.view->vertexSlots());
        result.unusedTriangles.push_back(band.view->triangleSlots());
        result.refused.insert(result.refused.end(), band.refused.begin(), band.refused.end());
    }
    std::sort(result.refused.begin(), result.refused.end());
    return result;
}

} // namespace terratin::detail

#pragma once
// Points inserted into a constrained TIN on several threads at once (the completion's cells):
// the plane is cut into bands of x holding as many points each, and each band's view of the one
// mesh (CdtMesh) inserts its points in order, refusing those whose insertion would reach outside
// the band, or split a constrained edge (its chains are shared). The refused ones go in
// afterwards on one thread. The bands, and so the mesh's numbering, depend on the points alone,
// never on the threads; the TIN itself is the one constrained Delaunay TIN of its vertices and
// constraints, whatever the order.

#include "cdt_mesh.hpp"

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace terratin::detail {

/// How many bands insertVertices cuts `points` points into: one per kPointsPerVertexZone (a
/// power of two, at most kMaxVertexZones).
inline constexpr std::size_t kPointsPerVertexZone = 2048;
inline constexpr unsigned kMaxVertexZones = 16;
[[nodiscard]] unsigned vertexZoneCount(std::size_t points);

/// What insertVerticesInZones left to do and to close up.
struct ZonedVertices {
    /// The points the bands refused, ascending.
    std::vector<std::size_t> refused;
    /// The points inserted.
    std::size_t inserted = 0;
    /// The slots the bands did not use (CdtMesh::compact's ranges: [next, end)).
    std::vector<SlotRange> unusedVertices;
    std::vector<SlotRange> unusedTriangles;
};

/// Inserts `points` (finite; point i with source index sources[i], its walk starting at
/// triangle near[i] of `mesh`) in `zones` bands of x on up to `threads` threads, then makes the
/// flips the bands' edges held back. A point on a vertex is skipped. `written`, when given,
/// receives 1 for every triangle written, as CdtMesh::recordWrites (on `mesh` too).
ZonedVertices insertVerticesInZones(CdtMesh& mesh, std::span<const Point3> points,
                                    std::span<const std::uint32_t> sources,
                                    std::span<const std::uint32_t> near, unsigned zones,
                                    unsigned threads, std::vector<std::uint8_t>* written);

} // namespace terratin::detail

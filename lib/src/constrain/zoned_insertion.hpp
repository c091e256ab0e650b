#pragma once
// The polylines inserted on several threads at once: the plane is cut into bands of x (zones),
// each polyline goes to the zone of its first point, and each zone's inserter (a view of the
// one mesh, CdtMesh) inserts its polylines in order, as far as it can without reaching outside
// its zone. What the zones stopped short (polylines near the bands' edges) goes on in bands of
// y the same way, by where each goes on, and what those refused afterwards on one thread. The
// zones, and so the TIN, depend on the polylines alone, never on the threads.

#include "constraint_inserter.hpp"
#include "polyline_insertion.hpp"
#include "terratin/constrain/insert_constraints.hpp"

#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

namespace terratin::detail {

/// How many zones the polylines of `constraints` go into: constraints.zones, or when that is 0
/// one per kPointsPerZone points (a power of two, at most kMaxZones).
inline constexpr std::size_t kPointsPerZone = 20000;
inline constexpr unsigned kMaxZones = 16;
[[nodiscard]] unsigned zoneCount(const ConstraintSet& constraints);

/// What insertInZones left to do and to close up.
struct ZonedInsertion {
    /// The polylines, or what is left of them, that the zones refused, in polyline order.
    std::vector<PolylineProgress> refused;
    /// The slots the zones did not use (CdtMesh::compact's ranges: [next, end)).
    std::vector<SlotRange> unusedVertices;
    std::vector<SlotRange> unusedTriangles;
};

/// Inserts the polylines of `constraints` (which must have their triangles) in `zones` bands of
/// x, then what they refused in `zones` bands of y, on up to `threads` threads; polyline k's
/// vertices go to vertices[k], its j-th segment is input segment firstOwner[k] + j - 1 (the chains
/// must have room for them: prepareChains). Then makes the flips the zones' edges held back. Call
/// before anything else changed the mesh, which polylineTriangles describe. While the zones
/// work, this thread calls `keepGoing` (when given) every kWatchInterval (watched_threads.hpp);
/// once it returns false the zones stop within kStepsPerPoll steps each, and this throws Cancelled
/// (as it does when a zone's inserter fails with it).
ZonedInsertion insertInZones(ConstraintInserter& inserter, const ConstraintSet& constraints,
                             unsigned zones, unsigned threads,
                             const std::vector<std::uint32_t>& firstOwner,
                             std::vector<std::vector<std::uint32_t>>& vertices,
                             const std::function<bool()>& keepGoing = {});

} // namespace terratin::detail

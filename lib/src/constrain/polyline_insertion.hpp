#pragma once
// One polyline into the constrained TIN, its points and then its segments, from where an
// earlier attempt stopped: a zone's inserter (zoned_insertion.hpp) may refuse part of a
// polyline, and the rest goes in afterwards on one thread.

#include "constraint_inserter.hpp"
#include "terratin/constrain/insert_constraints.hpp"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace terratin::detail {

/// How far a polyline has gone in.
struct PolylineProgress {
    std::size_t polyline = 0;
    /// Points [0, nextPoint) have their vertices; segments (j - 1, j) for j < nextSegment are
    /// in; `pieces`: what a zone left of segment nextSegment.
    std::size_t nextPoint = 0;
    std::size_t nextSegment = 1;
    std::vector<ConstraintInserter::Piece> pieces;
};

/// Inserts what is left of polyline `progress.polyline` of `constraints`: its points (an
/// existing vertex at a point's x and y is used; each point's vertex appended to `vertices`),
/// then its segments, the j-th as input segment firstOwner + j - 1. The search for point j
/// starts from triangle start[j], or, with `start` empty, from the point's triangle in
/// `constraints` when the polylines have them; kFromPreviousPoint in either says from the
/// previous point's vertex (for the first point, anywhere). With neither, it starts near the
/// previous point (a bucket grid for the first). A zone's inserter throws ZoneRefusal,
/// `progress` then saying how far the polyline went; when it refuses a point, the segments
/// between the points before it have gone in first, as far as the zone allows.
void insertPolyline(ConstraintInserter& inserter, const ConstraintSet& constraints,
                    std::vector<std::uint32_t>& vertices, std::uint32_t firstOwner,
                    PolylineProgress& progress, const std::vector<std::uint32_t>& start = {});

} // namespace terratin::detail

#pragma once
/// @file
/// Exact checks of a ConstrainedTin, in the manner of validateDelaunay (mesh_validation.hpp).

#include "terratin/constrain/constrained_tin.hpp"

#include <cstddef>
#include <string>
#include <vector>

namespace terratin {

/// What validateConstrainedDelaunay found. Counters count every violation; `problems`
/// describes the first few in words.
struct ConstrainedValidation {
    std::size_t badIndices = 0;            ///< vertex or neighbour index out of range, bad sizes
    std::size_t notCounterClockwise = 0;   ///< triangles with orientation <= 0 (exact)
    std::size_t asymmetricNeighbours = 0;  ///< neighbour links that are not mutual twins
    std::size_t asymmetricFlags = 0;       ///< twins of which only one is marked constrained
    std::size_t nonDelaunayEdges = 0;      ///< unconstrained edge failing the empty-circle test
    std::size_t unusedVertices = 0;        ///< vertices in no triangle
    std::size_t missingChainEdges = 0;     ///< consecutive chain vertices not joined by a
                                           ///< constrained edge
    std::size_t strayConstrainedEdges = 0; ///< constrained edges in no chain
    bool eulerHolds = false;               ///< V - E + F == 1 (a triangulated disk)
    bool areaMatchesHull = false; ///< triangle areas add up to the vertices' convex hull area
    std::vector<std::string> problems;

    [[nodiscard]] bool ok() const {
        return badIndices == 0 && notCounterClockwise == 0 && asymmetricNeighbours == 0 &&
               asymmetricFlags == 0 && nonDelaunayEdges == 0 && unusedVertices == 0 &&
               missingChainEdges == 0 && strayConstrainedEdges == 0 && eulerHolds &&
               areaMatchesHull;
    }
};

/// Checks, with exact predicates on the vertex coordinates: every triangle strictly
/// counter-clockwise; neighbour links mutual and across the same edge; constrained flags equal
/// on both half-edges; across every unconstrained interior edge the opposite vertex not strictly
/// inside the circumcircle (constrained edges are exempt); every vertex used; Euler's relation
/// for a disk; the triangles' area sum equal to the area of the convex hull of the vertices (up
/// to the rounding of the two sums); every pair of consecutive vertices of every chain joined by
/// a constrained edge, and every constrained edge on some chain. O(n log n) time (the hull),
/// O(n) memory.
ConstrainedValidation validateConstrainedDelaunay(const ConstrainedTin& tin);

} // namespace terratin

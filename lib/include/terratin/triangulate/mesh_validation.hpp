#pragma once
/// @file
/// Exact structural and Delaunay checks of a TinMesh, for tests, `terratin build --validate`
/// and anyone receiving a mesh from elsewhere.

#include "terratin/triangulate/tin_mesh.hpp"

#include <cstddef>
#include <string>
#include <vector>

namespace terratin {

/// What validateDelaunay found. Counters count every violation; `problems` describes the
/// first few in words.
struct MeshValidation {
    std::size_t badIndices = 0;           ///< vertex or neighbour index out of range
    std::size_t notCounterClockwise = 0;  ///< triangles with orientation <= 0 (exact)
    std::size_t asymmetricNeighbours = 0; ///< neighbour links that are not mutual twins
    std::size_t nonDelaunayEdges = 0;     ///< opposite vertex strictly inside a circumcircle
    std::size_t unusedVertices = 0;       ///< vertices in no triangle
    std::size_t boundaryProblems = 0;     ///< boundary not one convex counter-clockwise cycle
    bool eulerHolds = false;              ///< V - E + F == 1 (a triangulated disk)
    std::vector<std::string> problems;

    [[nodiscard]] bool ok() const {
        return badIndices == 0 && notCounterClockwise == 0 && asymmetricNeighbours == 0 &&
               nonDelaunayEdges == 0 && unusedVertices == 0 && boundaryProblems == 0 && eulerHolds;
    }
};

/// Checks, with exact predicates on the vertex coordinates: every triangle strictly
/// counter-clockwise; neighbour links mutual and across the same edge; across every interior
/// edge the opposite vertex not strictly inside the circumcircle (the empty-circle property);
/// every vertex used; Euler's relation for a disk; the boundary edges forming one closed
/// cycle that turns only left or straight (so the mesh covers a convex region, which with the
/// rest means the convex hull of its vertices). O(n) time and memory.
MeshValidation validateDelaunay(const TinMesh& mesh);

} // namespace terratin

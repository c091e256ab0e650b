#pragma once
// Inserting one segment u -> w by retriangulating the triangles it crosses (Anglada 1997): the
// crossed region, less the segment, is a polygon on each side, whose constrained Delaunay
// triangulation is built by choosing, for each edge from the segment outwards, the polygon's
// vertex whose circle with that edge holds no other vertex of it. Each new triangle is written
// once, where the flips of segment_flips.hpp flip each crossed edge away and then test again
// every edge they touched.
//
// Notation: the crossed edges run from the vertex right of the segment to the vertex left of it
// (walkCrossedEdges); the left chain is their left vertices in order from u, without repeats
// in a row, the right chain their right vertices. The left polygon is u, the left chain, w; the
// right polygon w, the right chain backwards, u.

#include "cdt_mesh.hpp"
#include "segment_flips.hpp"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace terratin::detail {

/// The most crossed edges a cavity is retriangulated for: choosing a polygon's vertices one by
/// one is quadratic in their number at worst, where flips are linear in the usual case.
inline constexpr std::size_t kMaxCavityCrossings = 64;

/// Scratch space of retriangulateCavity, kept to spare allocations per segment.
struct CavityScratch {
    /// The triangles the segment passes through, in order from u.
    std::vector<std::size_t> slots;
    std::vector<std::uint32_t> left;
    std::vector<std::uint32_t> right;
    /// The polygons' boundary half-edges as the region's triangles hold them: the left
    /// polygon's edges from u on, then the right polygon's from w on.
    std::vector<std::size_t> boundary;
    std::vector<std::size_t> rightBoundary;
    struct Pending {
        std::uint32_t a;
        std::uint32_t b;
        std::uint32_t first; // the polygon's vertices strictly between a and b: [first, last)
        std::uint32_t last;
        std::uint32_t parent; // the new triangle across a-b (none for the segment)
        std::uint32_t parentEdge;
    };
    std::vector<Pending> pending;
    std::vector<CdtMesh::CavityTriangle> triangles;
};

/// Replaces the triangles that the segment u -> crossed.end crosses (crossed as
/// walkCrossedEdges filled it, no constrained edge among them) by the constrained Delaunay
/// triangulations of the two polygons on either side of the segment, and returns the half-edge
/// u -> crossed.end (not yet marked constrained). Returns kNoHalfEdge, changing nothing, when
/// the segment crosses more than kMaxCavityCrossings edges, or when a vertex comes back in a
/// chain after others (the segment passes a vertex twice, which makes the region beside it no
/// polygon): flipSegmentIn handles those. O(k) for k crossed edges in the usual case, O(k^2)
/// at worst.
std::size_t retriangulateCavity(CdtMesh& mesh, std::uint32_t u, const CrossedEdges& crossed,
                                CavityScratch& scratch);

} // namespace terratin::detail

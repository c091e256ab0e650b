#include "segment_cavity.hpp"

#include "terratin/geometry/predicates.hpp"

#include <algorithm>

namespace terratin::detail {

namespace {

using CavityTriangle = CdtMesh::CavityTriangle;
using Pending = CavityScratch::Pending;
constexpr std::uint32_t kNone = 0xffffffffU;

bool hasRepeat(const std::vector<std::uint32_t>& chain) {
    for (auto v = chain.begin(); v != chain.end(); ++v)
        if (std::find(v + 1, chain.end(), *v) != chain.end())
            return true;
    return false;
}

// The triangles the walk passed through, the chains and the boundary half-edges, read from its
// crossed edges and entries.
// The first triangle (u, right, left) has u -> right and left -> u on the boundary; each
// middle one, entered by (left, right), the edge to its third vertex on that vertex's side;
// the last, entered by (left, right), right -> w and w -> left.
void readCavity(const CrossedEdges& crossed, CavityScratch& scratch) {
    const std::vector<CdtMesh::Edge>& edges = crossed.edges;
    scratch.slots.assign(1, edges.front().hint / 3);
    for (const std::size_t entry : crossed.entries)
        scratch.slots.push_back(entry / 3);
    scratch.left.assign(1, edges.front().b);
    scratch.right.assign(1, edges.front().a);
    scratch.boundary.assign(1, nextHalfEdge(edges.front().hint));
    scratch.rightBoundary.assign(1, previousHalfEdge(edges.front().hint));
    for (std::size_t j = 1; j < edges.size(); ++j) {
        const std::size_t entry = crossed.entries[j - 1];
        if (edges[j].hint == nextHalfEdge(entry)) {
            scratch.left.push_back(edges[j].b);
            scratch.boundary.push_back(previousHalfEdge(entry));
        } else {
            scratch.right.push_back(edges[j].a);
            scratch.rightBoundary.push_back(nextHalfEdge(entry));
        }
    }
    const std::size_t last = crossed.entries.back();
    scratch.boundary.push_back(previousHalfEdge(last));
    scratch.rightBoundary.push_back(nextHalfEdge(last));
    std::reverse(scratch.right.begin(), scratch.right.end());
    scratch.boundary.insert(scratch.boundary.end(), scratch.rightBoundary.rbegin(),
                            scratch.rightBoundary.rend());
}

// The triangulation of the polygon a, chain..., b, whose chain (in order from a to b) lies left
// of a -> b, appended to scratch.triangles, the first appended holding a -> b as its edge 0.
// The polygon's edge from its i-th vertex (a the 0th) to the next is the boundary half-edge
// boundaryOffset + i.
void triangulatePolygon(const CdtMesh& mesh, std::uint32_t a, std::uint32_t b,
                        const std::vector<std::uint32_t>& chain, std::size_t boundaryOffset,
                        CavityScratch& scratch) {
    std::vector<Pending>& pending = scratch.pending;
    std::vector<CavityTriangle>& triangles = scratch.triangles;
    pending.assign(1, {a, b, 0, static_cast<std::uint32_t>(chain.size()), kNone, 0});
    while (!pending.empty()) {
        const Pending edge = pending.back();
        pending.pop_back();
        if (edge.first == edge.last) {
            triangles[edge.parent].across[edge.parentEdge] =
                CavityTriangle::kCavityBoundary |
                static_cast<std::uint32_t>(boundaryOffset + edge.first);
            continue;
        }
        // The chain vertex whose circle through a and b holds no other: a vertex inside the
        // circle of the best so far has a circle that is, on this side, inside that one.
        const Point2 pa = mesh.xy(edge.a);
        const Point2 pb = mesh.xy(edge.b);
        std::uint32_t best = edge.first;
        for (std::uint32_t i = edge.first + 1; i < edge.last; ++i)
            if (predicates::incircleTieBroken(pa, pb, mesh.xy(chain[best]), mesh.xy(chain[i])) > 0)
                best = i;
        const std::uint32_t c = chain[best];
        const auto k = static_cast<std::uint32_t>(triangles.size());
        triangles.push_back({{edge.a, edge.b, c}, {edge.parent, kNone, kNone}});
        if (edge.parent != kNone)
            triangles[edge.parent].across[edge.parentEdge] = k;
        // Edge c -> a (edge 2) faces the polygon a, chain[first, best), c; edge b -> c (edge 1)
        // the polygon c, chain(best, last), b.
        pending.push_back({edge.a, c, edge.first, best, k, 2});
        pending.push_back({c, edge.b, best + 1, edge.last, k, 1});
    }
}

} // namespace

std::size_t retriangulateCavity(CdtMesh& mesh, std::uint32_t u, const CrossedEdges& crossed,
                                CavityScratch& scratch) {
    if (crossed.edges.empty() || crossed.edges.size() > kMaxCavityCrossings)
        return kNoHalfEdge;
    readCavity(crossed, scratch);
    if (hasRepeat(scratch.left) || hasRepeat(scratch.right))
        return kNoHalfEdge;

    const std::uint32_t w = crossed.end;
    scratch.triangles.clear();
    triangulatePolygon(mesh, u, w, scratch.left, 0, scratch);
    const auto rightFirst = static_cast<std::uint32_t>(scratch.triangles.size());
    triangulatePolygon(mesh, w, u, scratch.right, scratch.left.size() + 1, scratch);
    // The segment: edge 0 of each side's first triangle.
    scratch.triangles[0].across[0] = rightFirst;
    scratch.triangles[rightFirst].across[0] = 0;
    mesh.replaceCavity(scratch.slots, scratch.boundary, scratch.triangles);
    return 3 * scratch.slots[0];
}

} // namespace terratin::detail

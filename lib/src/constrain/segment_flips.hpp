#pragma once
// Inserting one segment u -> v between two vertices by flips (Sloan 1993, as Shewchuk's
// Triangle does): walk from u through the edges the segment crosses, up to v or to the first
// vertex w exactly on the segment; flip crossing edges away until u -> w is an edge; then
// Lawson flips, never across a constrained edge, restore the constrained Delaunay property on
// every edge the flips touched. The walk changes nothing, so when it meets a constrained edge
// the caller can split that edge at the crossing first.
//
// The inserter retriangulates the crossed region instead where it can (segment_cavity.hpp,
// which writes each new triangle once); the flips take the cases it leaves: a segment passing
// close by a vertex may cross every triangle around it, which puts that vertex inside the
// crossed region (the region beside the segment then has a slit to it), and segments crossing
// many edges, where choosing the polygons' vertices one by one would be quadratic. Flips need
// no such case.

#include "cdt_mesh.hpp"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace terratin::detail {

/// What the segment from u towards v meets first around u.
struct SegmentStart {
    enum class Kind { AlongEdge, IntoTriangle };
    Kind kind = Kind::AlongEdge;
    /// AlongEdge: a half-edge between u and `vertex` (either direction). IntoTriangle: the
    /// half-edge u -> p of the triangle the segment enters, p to its right.
    std::size_t halfEdge = kNoHalfEdge;
    /// AlongEdge: the vertex, v itself or the nearest vertex exactly on the segment.
    std::uint32_t vertex = 0;
};

/// Finds it by turning around u. O(degree of u). Precondition: u != v, both vertices.
SegmentStart findSegmentStart(const CdtMesh& mesh, std::uint32_t u, std::uint32_t v);

/// The edges a segment crosses, each as (vertex right of it, vertex left of it), in order from
/// u, and the vertex where the walk ended.
struct CrossedEdges {
    std::vector<CdtMesh::Edge> edges;
    std::uint32_t end = 0;
    /// The half-edge by which the segment enters each triangle after the first (the twin of
    /// each edge's hint, in the same order).
    std::vector<std::size_t> entries;
    /// Scratch space of flipSegmentIn, kept to spare an allocation per segment.
    std::vector<CdtMesh::Edge> queue;
    std::vector<std::size_t> touched;
};

/// Walks from the triangle of `start` (IntoTriangle) towards v, filling `crossed`. Returns
/// kNoHalfEdge when it reached a vertex (v or one exactly on the segment), else the constrained
/// half-edge (from its vertex right of the segment to its vertex left of it) that the segment
/// crosses; the mesh is not changed. O(triangles crossed).
std::size_t walkCrossedEdges(const CdtMesh& mesh, std::uint32_t u, std::uint32_t v,
                             const SegmentStart& start, CrossedEdges& crossed);

/// Flips the crossed edges until u -> crossed.end is an edge, restores the constrained
/// Delaunay property, and returns the half-edge between u and crossed.end (not yet marked
/// constrained). O(k) flips for k crossed edges in the usual case, O(k^2) at worst.
std::size_t flipSegmentIn(CdtMesh& mesh, std::uint32_t u, CrossedEdges& crossed);

} // namespace terratin::detail

#pragma once
/// @file
/// Randomized incremental Delaunay triangulation with a DAG point-location history
/// (Guibas, Knuth & Sharir 1992; de Berg et al., Computational Geometry, ch. 9; the base
/// algorithm of Kohout & Kolingerova's parallel methods, section 3.1).
///
/// Every triangle ever created is a node of one flat array. A leaf is a triangle of the current
/// triangulation and stores its three neighbours; an inner node is a triangle that was split
/// or flipped away and stores how to choose among its children, which are always allocated
/// consecutively. Point location walks from the root (the auxiliary triangle) to a leaf in
/// expected O(log n) orientation tests; insertion splits the leaf (or the two leaves sharing
/// the edge the point lies on) and restores the Delaunay property with Lawson flips.
/// Expected O(n log n) time and O(n) nodes for a random insertion order.

#include "node_arena.hpp"
#include "symbolic_predicates.hpp"

#include "terratin/progress.hpp"

#include <array>
#include <cstdint>
#include <span>
#include <vector>

namespace terratin::detail {

/// Sequential DAG triangulator over the finite points given at construction.
class DagTriangulator {
public:
    /// `points`: distinct points, not all collinear (see preparePoints); they must outlive the
    /// triangulator. The highest point becomes the finite corner of the auxiliary triangle
    /// and is inserted by construction.
    explicit DagTriangulator(std::span<const Point2> points);

    /// The finite corner of the auxiliary triangle (already part of the triangulation).
    [[nodiscard]] VertexId highestVertex() const { return m_highest; }

    /// Inserts the vertices of `order` one after the other; `order` must not contain
    /// highestVertex() nor any vertex twice. Calls `progress` now and then with the fraction
    /// of `order` done and throws Cancelled when it returns false.
    void insertAll(std::span<const VertexId> order, const ProgressCallback& progress);

    /// Inserts one vertex.
    void insert(VertexId q) { insertAtLeaf(locate(q), q); }

    /// Inserts q into `leaf`, a current leaf whose closed triangle contains q.
    void insertAtLeaf(NodeId leaf, VertexId q);

    /// Leaf whose closed triangle contains the finite vertex q, searched from `start` (the
    /// root by default, or any node whose closed triangle contains q).
    ///
    /// Safe to call from other threads while one thread inserts: it reads only vertex corners,
    /// which never change, and the links of nodes it has seen to be inner, which never change
    /// again. It then returns a node that was a leaf when read and may since have been split:
    /// the inserting thread completes the location from there.
    [[nodiscard]] NodeId locate(VertexId q, NodeId start = 0) const;

    /// The triangles with three finite corners, as TinMesh arrays: corners counter-clockwise
    /// and neighbours[3t+i] across the edge from corner i to corner i+1 (-1 on the hull).
    void extract(std::vector<std::uint32_t>& triangles, std::vector<std::int32_t>& neighbours) const;

    [[nodiscard]] std::size_t nodeCount() const { return m_nodes.size(); }
    [[nodiscard]] std::size_t memoryBytes() const { return m_nodes.bytesAllocated(); }

private:
    void setLeaf(NodeId id, VertexId a, VertexId b, VertexId c, NodeId na, NodeId nb, NodeId nc);
    /// Turns leaf `node` into an inner node; the release store publishes its children.
    void setInner(NodeId node, std::array<NodeId, 3> link, NodeId firstChild);
    void replaceNeighbour(NodeId node, NodeId from, NodeId to);
    void splitTriangle(NodeId t, VertexId p);
    void splitEdge(NodeId t, int edge, VertexId p);
    void legalize(VertexId p);
    void flip(NodeId t, int pos, NodeId u, int opposite);

    SymbolicPredicates m_predicates;
    NodeArena m_nodes;
    /// Triangles (node, position of the new point) whose edge opposite the new point must be
    /// checked; a member so its storage is reused between insertions.
    std::vector<std::pair<NodeId, int>> m_pending;
    VertexId m_highest = 0;
};

} // namespace terratin::detail

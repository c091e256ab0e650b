#pragma once
/// @file
/// Randomized incremental Delaunay triangulation with a DAG point-location history
/// (Guibas, Knuth & Sharir 1992; de Berg et al., Computational Geometry, ch. 9; the base
/// algorithm of Kohout & Kolingerova's parallel methods, section 3.1).
///
/// Every triangle ever created is a node of one arena. A leaf is a triangle of the current
/// triangulation and stores its three neighbours; an inner node is a triangle that was split
/// or flipped away and stores how to choose among its children, which are always allocated
/// consecutively. Point location walks from the root (the auxiliary triangle) to a leaf in
/// expected O(log n) orientation tests; insertion splits the leaf (or the two leaves sharing
/// the edge the point lies on) and restores the Delaunay property with Lawson flips.
/// Expected O(n log n) time and O(n) nodes for a random insertion order.
///
/// The editing operations take the caller's stack of pending edges and an owner tag for the
/// nodes they create, so that the parallel methods can run them from several threads, each
/// on triangles it holds (see batch_insertion.hpp and circumcircle_insertion.hpp).

#include "../mesh/node_arena.hpp"
#include "symbolic_predicates.hpp"

#include "terratin/progress.hpp"
#include "terratin/triangulate/tin_mesh.hpp"

#include <array>
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

namespace terratin::detail {

/// Triangles (node, position of the new point) whose edge opposite the new point must be
/// checked by Lawson's test.
using PendingEdges = std::vector<std::pair<NodeId, int>>;

constexpr int nextCorner(int i) {
    return i == 2 ? 0 : i + 1;
}
constexpr int previousCorner(int i) {
    return i == 0 ? 2 : i - 1;
}

/// DAG triangulator over the finite points given at construction. Aligned to a cache line:
/// the parallel methods' threads read it constantly, and it lives on a thread's stack.
class alignas(64) DagTriangulator {
public:
    /// `points`: distinct points, not all collinear (see preparePoints); they must outlive the
    /// insertions (extract() does not read them). The highest point becomes the finite corner
    /// of the auxiliary triangle and is inserted by construction.
    explicit DagTriangulator(std::span<const Point2> points);

    /// The finite corner of the auxiliary triangle (already part of the triangulation).
    [[nodiscard]] VertexId highestVertex() const { return m_highest; }
    /// The vertex the constructor makes highestVertex(): the highest, then rightmost point.
    [[nodiscard]] static VertexId highestOf(std::span<const Point2> points);

    /// Inserts the vertices of `order` one after the other; `order` must not contain
    /// highestVertex() nor any vertex twice. Calls `progress` now and then with the fraction
    /// of `order` done and throws Cancelled when it returns false.
    void insertAll(std::span<const VertexId> order, const ProgressCallback& progress);

    /// Node whose closed triangle contains q and that was a leaf when examined, found by a
    /// visibility walk from `start` (any node; an inner one is first descended to a leaf).
    /// Terminates on a Delaunay triangulation (Edelsbrunner 1989). Safe while other threads
    /// edit (see node_arena.hpp): a walk that a concurrent edit sends astray is bounded and
    /// then replaced by locate(q). Like locate, the leaf found may since have been split.
    [[nodiscard]] NodeId walk(VertexId q, NodeId start) const;

    /// Inserts q into `leaf`, a current leaf whose closed triangle contains q, and legalises.
    void insertAtLeaf(NodeId leaf, VertexId q);

    /// Leaf whose closed triangle contains the finite vertex q, searched from `start` (the
    /// root by default, or any node whose closed triangle contains q).
    ///
    /// Safe to call from other threads while threads edit: it reads only vertex corners,
    /// which never change, and the links of nodes it has seen to be inner, which never change
    /// again. It then returns a node that was a leaf when read and may since have been split.
    [[nodiscard]] NodeId locate(VertexId q, NodeId start = 0) const;

    /// For a leaf whose closed triangle contains q: the corner opposite the edge q lies on,
    /// or -1 when q is strictly inside.
    [[nodiscard]] int edgeContaining(NodeId leaf, VertexId q) const;

    /// Splits leaf t at p, strictly inside it; queues the three outer edges.
    void splitTriangle(NodeId t, VertexId p, PendingEdges& pending, std::uint32_t owner = 0);
    /// Splits leaf t and its neighbour across the edge opposite corner `edge` at p, which
    /// lies on that edge; queues the four outer edges.
    void splitEdge(NodeId t, int edge, VertexId p, PendingEdges& pending, std::uint32_t owner = 0);
    /// Flips the edge between t = (p, i, j) (p at `pos`) and u = (l, j, i) (l at `opposite`)
    /// into (p, l); queues the two new edges opposite p.
    void flip(NodeId t, int pos, NodeId u, int opposite, PendingEdges& pending,
              std::uint32_t owner = 0);
    /// Lawson's legalisation of the pending edges opposite the inserted vertex p.
    void legalize(VertexId p, PendingEdges& pending);

    /// Makes the current triangulation Delaunay when its illegal edges all lie on leaves with
    /// ids from `first` on (first = 0: any triangulation): checks every edge of those leaves,
    /// on up to `threads` threads, and flips from the illegal ones until none is left
    /// (Lawson's algorithm, which terminates from any triangulation; the flips run on the
    /// calling thread). Returns the number of flips.
    std::size_t repairEdgesFrom(NodeId first, unsigned threads = 1);

    /// The triangles with three finite corners, as TinMesh arrays: corners counter-clockwise
    /// and neighbours[3t+i] across the edge from corner i to corner i+1 (-1 on the hull).
    /// Uses up to `threads` threads; the result does not depend on it. Reads the DAG alone:
    /// the points may be gone by then. Numbers the leaves in their owner words, so no
    /// circum-circle insertion may follow (repairEdgesFrom and another extract() may).
    void extract(MeshArray<std::uint32_t>& triangles, MeshArray<std::int32_t>& neighbours,
                 unsigned threads = 1);

    [[nodiscard]] DagNode& node(NodeId id) { return m_nodes[id]; }
    [[nodiscard]] const DagNode& node(NodeId id) const { return m_nodes[id]; }
    [[nodiscard]] const SymbolicPredicates& predicates() const { return m_predicates; }
    [[nodiscard]] std::size_t nodeCount() const { return m_nodes.size(); }
    /// No node the calling thread creates from now on has a lower id than this.
    [[nodiscard]] NodeId lowestFutureNodeOfThisThread() const {
        return m_nodes.lowestFutureIdOfThisThread();
    }
    /// The node the calling thread created last (a leaf unless edited since), or the root.
    [[nodiscard]] NodeId newestNode() const {
        const NodeId newest = m_nodes.newestOfThisThread();
        return newest == kNoNode ? 0 : newest;
    }
    [[nodiscard]] std::size_t memoryBytes() const { return m_nodes.bytesAllocated(); }

private:
    void setLeaf(NodeId id, std::array<VertexId, 3> v, std::array<NodeId, 3> link,
                 std::uint32_t owner);
    /// Turns leaf `node` into an inner node; the release store publishes its children.
    void setInner(NodeId node, std::array<NodeId, 3> link, NodeId firstChild);
    void replaceNeighbour(NodeId node, NodeId from, NodeId to);
    /// True when the edge opposite corner `pos` of leaf t, shared with leaf u, is not
    /// locally Delaunay (u's far corner strictly inside t's circumcircle).
    [[nodiscard]] bool isIllegal(NodeId t, int pos, NodeId u) const;

    SymbolicPredicates m_predicates;
    NodeArena m_nodes;
    /// The sequential path's pending edges, kept to reuse the storage between insertions.
    PendingEdges m_pending;
    VertexId m_highest = 0;
};

} // namespace terratin::detail

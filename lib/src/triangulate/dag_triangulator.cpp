#include "dag_triangulator.hpp"

#include "../huge_pages.hpp"
#include "terratin/error.hpp"

#include "../parallel/parallel_for.hpp"

#include <algorithm>
#include <cassert>
#include <memory>
#include <thread>

namespace terratin::detail {

namespace {
constexpr int next(int i) {
    return nextCorner(i);
}
constexpr int prev(int i) {
    return previousCorner(i);
}

// Progress is reported every this many insertions: often enough for a smooth bar, rarely
// enough that the callback costs nothing measurable.
constexpr std::size_t kProgressInterval = 1U << 16;

// A visibility walk longer than this gives up and descends the DAG from the root instead.
// Sequential walks on a Delaunay triangulation always end; this bounds the rare walk that a
// concurrent edit sends in circles.
constexpr std::size_t kMaxWalkSteps = 1U << 16;
} // namespace

VertexId DagTriangulator::highestOf(std::span<const Point2> points) {
    VertexId highest = 0;
    for (VertexId v = 1; v < points.size(); ++v)
        if (SymbolicPredicates::compareHeight(points[highest], points[v]) > 0)
            highest = v;
    return highest;
}

DagTriangulator::DagTriangulator(std::span<const Point2> points)
    : m_predicates(points), m_highest(highestOf(points)) {
    // The auxiliary triangle (p0, p-2, p-1) is counter-clockwise (symbolic_predicates.hpp).
    const NodeId root = m_nodes.allocate(1);
    setLeaf(root, {m_highest, m_predicates.farLeft(), m_predicates.farRight()},
            {kNoNode, kNoNode, kNoNode}, 0);
}

void DagTriangulator::setLeaf(NodeId id, std::array<VertexId, 3> v, std::array<NodeId, 3> link,
                              std::uint32_t owner) {
    DagNode& node = m_nodes[id];
    node.v = v;
    node.link = link; // not yet published: no other thread can see this node
    node.firstChild.store(kNoNode, std::memory_order_relaxed);
    node.owner.store(owner, std::memory_order_relaxed);
}

void DagTriangulator::setInner(NodeId node, std::array<NodeId, 3> link, NodeId firstChild) {
    // Walkers may be reading this leaf's links: mark it busy first (node_arena.hpp).
    DagNode& inner = m_nodes[node];
    inner.firstChild.store(kBusyNode, std::memory_order_relaxed);
    for (int i = 0; i < 3; ++i)
        inner.storeLink(i, link[static_cast<std::size_t>(i)]);
    inner.firstChild.store(firstChild, std::memory_order_release);
}

void DagTriangulator::replaceNeighbour(NodeId node, NodeId from, NodeId to) {
    if (node == kNoNode)
        return;
    DagNode& neighbour = m_nodes[node];
    neighbour.storeLink(neighbour.linkIndexOf(from), to);
}

NodeId DagTriangulator::locate(VertexId q, NodeId start) const {
    NodeId n = start;
    for (;;) {
        const DagNode& node = m_nodes[n];
        const NodeId c = node.firstChild.load(std::memory_order_acquire);
        if (c == kNoNode)
            return n;
        if (c == kBusyNode) {
            // Another thread is publishing this node's children: a few stores away.
            std::this_thread::yield();
            continue;
        }
        if (node.link[1] == kNoNode) {
            // Three children, child i being the node with corner i replaced by p. The rays
            // from p to the corners separate them; two orientation tests pick the wedge.
            const VertexId p = node.link[0];
            if (m_predicates.orient(p, node.v[0], q) >= 0)
                n = m_predicates.orient(p, node.v[1], q) <= 0 ? c + 2 : c;
            else
                n = m_predicates.orient(p, node.v[2], q) >= 0 ? c + 1 : c;
        } else {
            n = m_predicates.orient(node.link[0], node.link[1], q) >= 0 ? c : c + 1;
        }
    }
}

void DagTriangulator::insertAll(std::span<const VertexId> order, const ProgressCallback& progress) {
    for (std::size_t i = 0; i < order.size(); ++i) {
        if (progress && i % kProgressInterval == 0 &&
            !progress(static_cast<double>(i) / static_cast<double>(order.size()), "triangulating"))
            throw Cancelled("Triangulator: cancelled");
        insertAtLeaf(locate(order[i]), order[i]);
    }
}

NodeId DagTriangulator::walk(VertexId q, NodeId start) const {
    NodeId t = start;
    for (std::size_t steps = 0;; ++steps) {
        if (steps == kMaxWalkSteps)
            return locate(q); // a walk through a mesh others keep changing might not end
        // An inner node (a stale start, or a neighbour split since its link was read) is left
        // by descending to one of its leaves: the walk goes on from there.
        t = locate(q, t);
        const DagNode& node = m_nodes[t];
        int exit = 0;
        while (exit < 3 && m_predicates.orient(node.v[next(exit)], node.v[prev(exit)], q) >= 0)
            ++exit;
        if (exit == 3)
            return t;
        // q is strictly beyond this edge, so the edge is not one of the auxiliary triangle's
        // (every point is inside it) and the neighbour exists. The link is a neighbour only if
        // the node was still a leaf after reading it (node_arena.hpp).
        const NodeId neighbour = node.loadLink(exit);
        if (node.firstChild.load(std::memory_order_relaxed) == kNoNode)
            t = neighbour;
    }
}

int DagTriangulator::edgeContaining(NodeId leaf, VertexId q) const {
    const std::array<VertexId, 3> v = m_nodes[leaf].v;
    for (int e = 0; e < 3; ++e) {
        // Only an edge between two finite vertices can pass through q: with a symbolic end
        // the orientation is a strict height comparison, never zero for q distinct.
        if (m_predicates.orient(v[next(e)], v[prev(e)], q) == 0)
            return e;
    }
    return -1;
}

void DagTriangulator::insertAtLeaf(NodeId leaf, VertexId q) {
    const int edge = edgeContaining(leaf, q);
    if (edge >= 0)
        splitEdge(leaf, edge, q, m_pending);
    else
        splitTriangle(leaf, q, m_pending);
    legalize(q, m_pending);
}

void DagTriangulator::splitTriangle(NodeId t, VertexId p, PendingEdges& pending,
                                    std::uint32_t owner) {
    const std::array<VertexId, 3> corner = m_nodes[t].v;
    const std::array<NodeId, 3> outer = m_nodes[t].link;
    const NodeId first = m_nodes.allocate(3);
    for (int i = 0; i < 3; ++i) {
        std::array<VertexId, 3> v = corner;
        v[i] = p;
        std::array<NodeId, 3> link{};
        link[i] = outer[i];
        link[next(i)] = first + next(i);
        link[prev(i)] = first + prev(i);
        setLeaf(first + i, v, link, owner);
    }
    for (int i = 0; i < 3; ++i)
        replaceNeighbour(outer[i], t, first + i);
    setInner(t, {p, kNoNode, kNoNode}, first);
    for (int i = 0; i < 3; ++i)
        pending.emplace_back(first + i, i);
}

void DagTriangulator::splitEdge(NodeId t, int edge, VertexId p, PendingEdges& pending,
                                std::uint32_t owner) {
    // t = (a, b, c) with p on the edge (b, c); u = (d, c, b) is the triangle beyond it. The
    // edge is finite, hence interior to the auxiliary triangle, so u exists.
    const DagNode& tNode = m_nodes[t];
    const VertexId a = tNode.v[edge];
    const VertexId b = tNode.v[next(edge)];
    const VertexId c = tNode.v[prev(edge)];
    const NodeId u = tNode.link[edge];
    assert(u != kNoNode);
    const DagNode& uNode = m_nodes[u];
    const int m = uNode.linkIndexOf(t);
    const VertexId d = uNode.v[m];
    const NodeId outerAB = tNode.link[prev(edge)];
    const NodeId outerCA = tNode.link[next(edge)];
    const NodeId outerDC = uNode.link[prev(m)];
    const NodeId outerBD = uNode.link[next(m)];

    const NodeId t0 = m_nodes.allocate(4);
    const NodeId t1 = t0 + 1;
    const NodeId u0 = t0 + 2;
    const NodeId u1 = t0 + 3;
    setLeaf(t0, {a, b, p}, {u1, t1, outerAB}, owner);
    setLeaf(t1, {a, p, c}, {u0, outerCA, t0}, owner);
    setLeaf(u0, {d, c, p}, {t1, u1, outerDC}, owner);
    setLeaf(u1, {d, p, b}, {t0, outerBD, u0}, owner);
    replaceNeighbour(outerAB, t, t0);
    replaceNeighbour(outerCA, t, t1);
    replaceNeighbour(outerDC, u, u0);
    replaceNeighbour(outerBD, u, u1);

    // (a, b, p) lies left of p -> a, (d, c, p) left of p -> d.
    setInner(t, {p, a, kNoNode}, t0);
    setInner(u, {p, d, kNoNode}, u0);
    pending.emplace_back(t0, 2);
    pending.emplace_back(t1, 1);
    pending.emplace_back(u0, 2);
    pending.emplace_back(u1, 1);
}

void DagTriangulator::legalize(VertexId p, PendingEdges& pending) {
    while (!pending.empty()) {
        const auto [t, pos] = pending.back();
        pending.pop_back();
        const DagNode& tNode = m_nodes[t];
        const NodeId u = tNode.link[pos];
        if (u == kNoNode)
            continue; // an edge of the auxiliary triangle
        const DagNode& uNode = m_nodes[u];
        const int m = uNode.linkIndexOf(t);
        if (m_predicates.shouldFlip(tNode.v[next(pos)], tNode.v[prev(pos)], p, uNode.v[m]))
            flip(t, pos, u, m, pending);
    }
}

void DagTriangulator::flip(NodeId t, int pos, NodeId u, int m, PendingEdges& pending,
                           std::uint32_t owner) {
    // t = (p, i, j), u = (l, j, i); the edge (i, j) becomes (p, l).
    const DagNode& tNode = m_nodes[t];
    const DagNode& uNode = m_nodes[u];
    const VertexId p = tNode.v[pos];
    const VertexId i = tNode.v[next(pos)];
    const VertexId l = uNode.v[m];
    const VertexId j = tNode.v[prev(pos)];
    const NodeId outerPI = tNode.link[prev(pos)];
    const NodeId outerJP = tNode.link[next(pos)];
    const NodeId outerIL = uNode.link[next(m)];
    const NodeId outerLJ = uNode.link[prev(m)];

    const NodeId t1 = m_nodes.allocate(2);
    const NodeId t2 = t1 + 1;
    setLeaf(t1, {p, i, l}, {outerIL, t2, outerPI}, owner);
    setLeaf(t2, {p, l, j}, {outerLJ, outerJP, t1}, owner);
    replaceNeighbour(outerPI, t, t1);
    replaceNeighbour(outerIL, u, t1);
    replaceNeighbour(outerLJ, u, t2);
    replaceNeighbour(outerJP, t, t2);

    // (p, i, l) lies left of l -> p.
    setInner(t, {l, p, kNoNode}, t1);
    setInner(u, {l, p, kNoNode}, t1);
    pending.emplace_back(t1, 0);
    pending.emplace_back(t2, 0);
}

bool DagTriangulator::isIllegal(NodeId t, int pos, NodeId u) const {
    const DagNode& tNode = m_nodes[t];
    const DagNode& uNode = m_nodes[u];
    const int m = uNode.linkIndexOf(t);
    return m_predicates.incircle(tNode.v[next(pos)], tNode.v[prev(pos)], tNode.v[pos], uNode.v[m]) >
           0;
}

std::size_t DagTriangulator::repairEdgesFrom(NodeId first, unsigned threads) {
    // Every edge of the leaves from `first` on is checked; an edge between two of them only
    // from the one with the lower id (the in-circle determinant is alternating, so the other
    // side gives the same answer). Only the illegal ones start the flips. A flipped edge
    // queues its four surrounding edges (the new triangles' edges away from the flipped
    // diagonal): no other edge's legality changes.
    const std::size_t nodeCount = m_nodes.size();
    const std::size_t checked = nodeCount - std::min<std::size_t>(first, nodeCount);
    std::vector<PendingEdges> illegal(parallelForThreads(checked, threads));
    parallelFor(checked, threads, [&](unsigned block, std::size_t begin, std::size_t end) {
        for (std::size_t n = first + begin; n < first + end; ++n) {
            const auto t = static_cast<NodeId>(n);
            const DagNode& tNode = m_nodes[t];
            if (!tNode.isLeaf() || tNode.v[0] == kNoNode)
                continue;
            for (int pos = 0; pos < 3; ++pos) {
                const NodeId u = tNode.link[pos];
                if (u != kNoNode && (u > t || u < first) && isIllegal(t, pos, u))
                    illegal[block].emplace_back(t, pos);
            }
        }
    });
    PendingEdges work;
    for (const PendingEdges& own : illegal)
        work.insert(work.end(), own.begin(), own.end());
    std::size_t flips = 0;
    PendingEdges created;
    while (!work.empty()) {
        const auto [t, pos] = work.back();
        work.pop_back();
        const DagNode& tNode = m_nodes[t];
        if (!tNode.isLeaf())
            continue;
        const NodeId u = tNode.link[pos];
        if (u == kNoNode)
            continue;
        if (!isIllegal(t, pos, u))
            continue;
        const DagNode& uNode = m_nodes[u];
        const int m = uNode.linkIndexOf(t);
        flip(t, pos, u, m, created);
        ++flips;
        // The new triangles are (k, i, l) and (k, l, j), k = the old tNode.v[pos]: their four
        // edges other than the new diagonal (opposite i in the first, j in the second) may
        // now fail.
        const NodeId left = created[0].first;
        const NodeId right = created[1].first;
        created.clear();
        work.insert(work.end(), {{left, 0}, {left, 2}, {right, 0}, {right, 1}});
    }
    return flips;
}

namespace {

// The extraction's three passes, each on every block of the arena: list the leaves, number
// the output triangles (finite leaves) after the blocks before theirs, write corners and
// neighbours. Three passes, since a neighbour may be in any block.

/// The leaves of one contiguous block of the arena, by id.
struct BlockLeaves {
    /// With three finite corners: the output triangles. On huge pages: a quarter of the
    /// arena's entries.
    HugePageArray<NodeId> finite;
    /// With a symbolic corner: outside the mesh.
    HugePageArray<NodeId> outside;
};

std::vector<BlockLeaves> leavesByBlock(const NodeArena& nodes, const SymbolicPredicates& predicates,
                                       unsigned threads) {
    const std::size_t nodeCount = nodes.size();
    const auto isFinite = [&predicates](const DagNode& node) {
        return predicates.isFinite(node.v[0]) && predicates.isFinite(node.v[1]) &&
               predicates.isFinite(node.v[2]);
    };
    std::vector<BlockLeaves> blockLeaves(parallelForThreads(nodeCount, threads));
    parallelFor(nodeCount, threads, [&](unsigned block, std::size_t begin, std::size_t end) {
        BlockLeaves& leaves = blockLeaves[block];
        leaves.finite.reserve((end - begin) / 4);
        for (std::size_t n = begin; n < end; ++n) {
            const DagNode& node = nodes[static_cast<NodeId>(n)];
            if (node.isLeaf())
                (isFinite(node) ? leaves.finite : leaves.outside).push_back(static_cast<NodeId>(n));
        }
    });
    return blockLeaves;
}

// The output index of every leaf, kOutside outside the mesh, is kept in its owner word: the
// insertions are over, so the word is free, and the corners beside it are read anyway. (An
// array of one entry per node took 37 MB of fresh pages per million points.)
constexpr std::uint32_t kOutside = 0xFFFFFFFFU; // -1 as an int32_t

/// Numbers every block's finite leaves from blockFirst[block] on; returns blockFirst, whose
/// last entry is the number of output triangles.
std::vector<std::size_t> numberLeaves(NodeArena& nodes, const std::vector<BlockLeaves>& blockLeaves,
                                      unsigned threads) {
    std::vector<std::size_t> blockFirst(blockLeaves.size() + 1, 0);
    for (std::size_t block = 0; block < blockLeaves.size(); ++block)
        blockFirst[block + 1] = blockFirst[block] + blockLeaves[block].finite.size();
    const auto setOutput = [&nodes](NodeId n, std::size_t output) {
        nodes[n].owner.store(static_cast<std::uint32_t>(output), std::memory_order_relaxed);
    };
    parallelFor(nodes.size(), threads, [&](unsigned block, std::size_t, std::size_t) {
        const BlockLeaves& leaves = blockLeaves[block];
        for (std::size_t k = 0; k < leaves.finite.size(); ++k)
            setOutput(leaves.finite[k], blockFirst[block] + k);
        for (const NodeId n : leaves.outside)
            setOutput(n, kOutside);
    });
    return blockFirst;
}

} // namespace

void DagTriangulator::extract(MeshArray<std::uint32_t>& triangles,
                              MeshArray<std::int32_t>& neighbours, unsigned threads) {
    const std::vector<BlockLeaves> blockLeaves = leavesByBlock(m_nodes, m_predicates, threads);
    const std::vector<std::size_t> blockFirst = numberLeaves(m_nodes, blockLeaves, threads);
    const auto outputOf = [this](NodeId n) {
        return static_cast<std::int32_t>(m_nodes[n].owner.load(std::memory_order_relaxed));
    };
    triangles.resize(3 * blockFirst.back());
    neighbours.resize(3 * blockFirst.back());
    parallelFor(m_nodes.size(), threads, [&](unsigned block, std::size_t, std::size_t) {
        const HugePageArray<NodeId>& outputs = blockLeaves[block].finite;
        for (std::size_t k = 0; k < outputs.size(); ++k) {
            const DagNode& node = m_nodes[outputs[k]];
            const std::size_t t = blockFirst[block] + k;
            for (int i = 0; i < 3; ++i) {
                triangles[3 * t + i] = node.v[i];
                // The edge from corner i to corner i+1 is opposite corner i+2.
                const NodeId across = node.link[prev(i)];
                neighbours[3 * t + i] = across == kNoNode ? -1 : outputOf(across);
            }
        }
    });
}

} // namespace terratin::detail

#pragma once
/// @file
/// Stable-address storage for the DAG: fixed-size chunks that never move, so threads may
/// follow node ids while other threads append nodes (a std::vector would reallocate under
/// them). Chunks are large, 2 MiB aligned and advised to use transparent huge pages, because
/// point location is a chain of dependent loads across the whole DAG and TLB misses dominate.

#include <array>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <mutex>

namespace terratin::detail {

using VertexId = std::uint32_t;
using NodeId = std::uint32_t;
inline constexpr NodeId kNoNode = 0xFFFFFFFFU;

/// One triangle of the history, 32 bytes.
///
/// Concurrency contract: `v` is written once, before the node is published (by the release
/// store of its parent's firstChild, or before threads start for the root). `link` of a leaf
/// is changed only by a thread that owns the leaf; readers that do not own it read `link` only
/// after an acquire load of firstChild has shown the node is inner, from when on `link` and
/// `firstChild` never change again.
struct DagNode {
    /// Corners, counter-clockwise.
    std::array<VertexId, 3> v;
    /// Leaf: link[i] is the leaf across the edge opposite v[i] (kNoNode on the auxiliary
    /// triangle's boundary). Inner node with three children: link = {inserted vertex, kNoNode,
    /// kNoNode}. Inner node with two children: link = {u, w, kNoNode}: the first child holds
    /// the points q with orient(u, w, q) >= 0, the second the others.
    std::array<NodeId, 3> link;
    /// kNoNode for a leaf, else the first of the consecutive children.
    std::atomic<NodeId> firstChild;
    /// Circum-circle method only: 0 when free, else 1 + the index of the worker that holds
    /// the triangle exclusively (see circumcircle_insertion.hpp).
    std::atomic<std::uint32_t> owner;

    [[nodiscard]] bool isLeaf() const {
        return firstChild.load(std::memory_order_acquire) == kNoNode;
    }
};

/// Appendable, never-moving array of DagNode with 32-bit ids.
class NodeArena {
public:
    static constexpr unsigned kChunkBits = 17;
    static constexpr std::size_t kChunkNodes = std::size_t{1} << kChunkBits;
    static constexpr std::size_t kMaxChunks = (std::size_t{1} << 32U) >> kChunkBits;

    NodeArena();
    ~NodeArena();
    NodeArena(const NodeArena&) = delete;
    NodeArena& operator=(const NodeArena&) = delete;

    DagNode& operator[](NodeId id) {
        return m_chunks[id >> kChunkBits].load(std::memory_order_acquire)[id & (kChunkNodes - 1)];
    }
    const DagNode& operator[](NodeId id) const {
        return m_chunks[id >> kChunkBits].load(std::memory_order_acquire)[id & (kChunkNodes - 1)];
    }

    /// Reserves `count` (at most 4) consecutive ids in one chunk and returns the first; the
    /// nodes are uninitialised leaves to be filled by the caller before publication.
    /// Thread-safe. Throws std::length_error past 2^32 - 2 nodes.
    NodeId allocate(unsigned count);

    /// Ids handed out so far (including the few skipped at chunk ends).
    [[nodiscard]] std::size_t size() const { return m_next.load(std::memory_order_relaxed); }
    /// Bytes of node storage allocated.
    [[nodiscard]] std::size_t bytesAllocated() const {
        return m_chunkCount.load(std::memory_order_relaxed) * kChunkNodes * sizeof(DagNode);
    }

private:
    DagNode* chunkFor(std::size_t chunk);

    std::unique_ptr<std::atomic<DagNode*>[]> m_chunks;
    std::atomic<std::size_t> m_next{0};
    std::atomic<std::size_t> m_chunkCount{0};
    std::mutex m_growth;
};

} // namespace terratin::detail

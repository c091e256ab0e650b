#pragma once
/// @file
/// The triangle node of the DAG history and its stable-address storage, with the vertex and
/// node ids that the triangulators and the refiner share. Fixed-size chunks never move, so
/// threads may follow node ids while other threads append nodes (a std::vector would
/// reallocate under them). Chunks are large, 2 MiB aligned and advised to use transparent huge
/// pages, because point location is a chain of dependent loads across the whole DAG and TLB
/// misses dominate.

#include <array>
#include <atomic>
#include <cassert>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <mutex>

namespace terratin::detail {

using VertexId = std::uint32_t;
using NodeId = std::uint32_t;
inline constexpr NodeId kNoNode = 0xFFFFFFFFU;
/// firstChild of a node that is becoming inner: its links are being rewritten and its
/// children are not published yet. Never a node id (the arena stops below it).
inline constexpr NodeId kBusyNode = 0xFFFFFFFEU;

/// How DagNode::linkIndexOf reads the links.
enum class LinkRead { Plain, Published };

/// One triangle of the history.
///
/// Concurrency contract: `v` is written once, before the node is published (by the release
/// store of its parent's firstChild or of a neighbour's link, or before threads start for the
/// root). `link` of a leaf is changed only by a thread that owns the leaf, always through
/// storeLink (release), and read by other threads only through loadLink (acquire), so a
/// node reached through a link is fully initialised. A leaf becomes inner in three steps:
/// firstChild = kBusyNode, the links rewritten to the children's selection data, firstChild =
/// the first child (release); from then on `link` and `firstChild` never change again. A
/// reader that loads a leaf's link and then still sees firstChild == kNoNode therefore holds
/// a real neighbour id (see DagTriangulator::walk).
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
    /// Circum-circle method only: 0 when free, else the owner tag of the worker's attempt that
    /// holds the triangle exclusively (OwnerTag in triangulate/owner_tag.hpp: the attempt
    /// number above the worker's index + 1). Once the insertions are over,
    /// DagTriangulator::extract numbers the leaves here.
    std::atomic<std::uint32_t> owner;

    [[nodiscard]] bool isLeaf() const {
        return firstChild.load(std::memory_order_acquire) == kNoNode;
    }
    /// link[i] as published by another thread's storeLink.
    [[nodiscard]] NodeId loadLink(int i) const {
        // atomic_ref has no const form in C++20; the load does not modify the link.
        return std::atomic_ref<NodeId>(const_cast<NodeId&>(link[static_cast<std::size_t>(i)]))
            .load(std::memory_order_acquire);
    }
    void storeLink(int i, NodeId neighbour) {
        std::atomic_ref<NodeId>(link[static_cast<std::size_t>(i)])
            .store(neighbour, std::memory_order_release);
    }

    /// The position i with link[i] == neighbour, which must be one of this leaf's links.
    /// LinkRead::Plain reads the links of a leaf no other thread edits meanwhile;
    /// LinkRead::Published loads them (loadLink) for a leaf whose other links another thread
    /// may be rewriting.
    template <LinkRead kRead = LinkRead::Plain>
    [[nodiscard]] int linkIndexOf(NodeId neighbour) const {
        int i = 0;
        while (readLink<kRead>(i) != neighbour) {
            ++i;
            assert(i < 3 && "neighbour links are not symmetric");
        }
        return i;
    }

private:
    template <LinkRead kRead> [[nodiscard]] NodeId readLink(int i) const {
        if constexpr (kRead == LinkRead::Published)
            return loadLink(i);
        else
            return link[static_cast<std::size_t>(i)];
    }
};
// Two nodes to a cache line, neither straddling two (docs/algorithms.md quotes the size).
static_assert(sizeof(DagNode) == 32);

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
    /// nodes are blank leaves to be filled by the caller before publication. Thread-safe:
    /// each thread takes ids from a block of kBlockNodes it reserved with one atomic add, so
    /// threads neither contend for a shared counter on every triangle nor write nodes that
    /// share a cache line. Throws std::length_error past 2^32 - 2 nodes.
    NodeId allocate(unsigned count);

    /// The id the calling thread allocated last in this arena, or kNoNode.
    [[nodiscard]] NodeId newestOfThisThread() const;
    /// A lower bound on the ids the calling thread allocates from now on: its current block's
    /// next id, and every later block starts above every block reserved before it.
    [[nodiscard]] NodeId lowestFutureIdOfThisThread() const;

    /// Nodes per block a thread reserves. Every id reserved is initialised as a dead node (a
    /// leaf with no finite corner, which every traversal of the whole arena ignores) until
    /// allocated, so ids a thread reserved and never used are harmless.
    static constexpr std::size_t kBlockNodes = 512;

    /// Ids handed out so far, including reserved and unused ones (dead nodes).
    [[nodiscard]] std::size_t size() const { return m_next.load(std::memory_order_relaxed); }
    /// Bytes of node storage allocated.
    [[nodiscard]] std::size_t bytesAllocated() const {
        return m_chunkCount.load(std::memory_order_relaxed) * kChunkNodes * sizeof(DagNode);
    }

private:
    DagNode* chunkFor(std::size_t chunk);

    /// Distinguishes this arena from every other, past or future, in the threads' caches of
    /// their current block.
    const std::uint64_t m_generation;
    std::unique_ptr<std::atomic<DagNode*>[]> m_chunks;
    /// Away from m_chunks, which every node access reads: each block reservation writes it.
    alignas(64) std::atomic<std::size_t> m_next{0};
    std::atomic<std::size_t> m_chunkCount{0};
    std::mutex m_growth;
};

} // namespace terratin::detail

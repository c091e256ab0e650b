#include "node_arena.hpp"

#include "../huge_pages.hpp"

#include <cstdlib>
#include <new>
#include <stdexcept>

namespace terratin::detail {

namespace {
// Chunks are on huge pages (huge_pages.hpp): the triangulator reads them at random.
constexpr std::size_t kChunkBytes = NodeArena::kChunkNodes * sizeof(DagNode);
static_assert(NodeArena::kChunkNodes % NodeArena::kBlockNodes == 0,
              "a block must never straddle two chunks");

std::atomic<std::uint64_t> nextGeneration{1};

// The block of ids the calling thread is allocating from, in the arena of that generation.
struct ThreadBlock {
    std::uint64_t generation = 0;
    std::size_t next = 0;
    std::size_t end = 0;
};
// initial-exec: the executables' own TLS model, also in the Python module (a shared object),
// where the default for position-independent code would call __tls_get_addr on every
// allocation. The block is small enough for glibc's static TLS reserve for dlopen.
[[gnu::tls_model("initial-exec")]] thread_local ThreadBlock threadBlock;
} // namespace

NodeArena::NodeArena()
    : m_generation(nextGeneration.fetch_add(1, std::memory_order_relaxed)),
      m_chunks(new std::atomic<DagNode*>[kMaxChunks]) {
    for (std::size_t i = 0; i < kMaxChunks; ++i)
        m_chunks[i].store(nullptr, std::memory_order_relaxed);
}

NodeArena::~NodeArena() {
    for (std::size_t i = 0; i < kMaxChunks; ++i)
        releaseHugePages(m_chunks[i].load(std::memory_order_relaxed), kChunkBytes);
}

DagNode* NodeArena::chunkFor(std::size_t chunk) {
    DagNode* nodes = m_chunks[chunk].load(std::memory_order_acquire);
    if (nodes != nullptr)
        return nodes;
    const std::lock_guard lock(m_growth);
    nodes = m_chunks[chunk].load(std::memory_order_acquire);
    if (nodes != nullptr)
        return nodes;
    nodes = static_cast<DagNode*>(allocateOnHugePages(kChunkBytes));
    m_chunks[chunk].store(nodes, std::memory_order_release);
    m_chunkCount.fetch_add(1, std::memory_order_relaxed);
    return nodes;
}

NodeId NodeArena::allocate(unsigned count) {
    ThreadBlock& block = threadBlock;
    if (block.generation != m_generation || block.next + count > block.end) {
        const std::size_t start = m_next.fetch_add(kBlockNodes, std::memory_order_relaxed);
        if (start + kBlockNodes > kBusyNode)
            throw std::length_error("Triangulator: more than 2^32 triangles in the history");
        DagNode* nodes = chunkFor(start >> kChunkBits) + (start & (kChunkNodes - 1));
        for (std::size_t i = 0; i < kBlockNodes; ++i)
            new (&nodes[i])
                DagNode{{kNoNode, kNoNode, kNoNode}, {kNoNode, kNoNode, kNoNode}, kNoNode, 0};
        block = {m_generation, start, start + kBlockNodes};
    }
    const std::size_t first = block.next;
    block.next += count;
    return static_cast<NodeId>(first);
}

NodeId NodeArena::newestOfThisThread() const {
    const ThreadBlock& block = threadBlock;
    if (block.generation != m_generation || block.next == 0)
        return kNoNode;
    return static_cast<NodeId>(block.next - 1);
}

NodeId NodeArena::lowestFutureIdOfThisThread() const {
    const ThreadBlock& block = threadBlock;
    if (block.generation == m_generation)
        return static_cast<NodeId>(block.next);
    return static_cast<NodeId>(m_next.load(std::memory_order_relaxed));
}

} // namespace terratin::detail

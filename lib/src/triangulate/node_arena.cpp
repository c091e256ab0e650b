#include "node_arena.hpp"

#include <cstdlib>
#include <new>
#include <stdexcept>

#include <sys/mman.h>

namespace terratin::detail {

namespace {
// Transparent huge pages are 2 MiB on x86-64 and arm64; aligning chunks to them lets the kernel
// back each chunk with few large pages.
constexpr std::size_t kHugePageBytes = std::size_t{2} << 20U;
constexpr std::size_t kChunkBytes = NodeArena::kChunkNodes * sizeof(DagNode);
} // namespace

NodeArena::NodeArena() : m_chunks(new std::atomic<DagNode*>[kMaxChunks]) {
    for (std::size_t i = 0; i < kMaxChunks; ++i)
        m_chunks[i].store(nullptr, std::memory_order_relaxed);
}

NodeArena::~NodeArena() {
    for (std::size_t i = 0; i < kMaxChunks; ++i)
        std::free(m_chunks[i].load(std::memory_order_relaxed));
}

DagNode* NodeArena::chunkFor(std::size_t chunk) {
    DagNode* nodes = m_chunks[chunk].load(std::memory_order_acquire);
    if (nodes != nullptr)
        return nodes;
    const std::lock_guard lock(m_growth);
    nodes = m_chunks[chunk].load(std::memory_order_acquire);
    if (nodes != nullptr)
        return nodes;
    void* memory = std::aligned_alloc(kHugePageBytes, (kChunkBytes + kHugePageBytes - 1) /
                                                          kHugePageBytes * kHugePageBytes);
    if (memory == nullptr)
        throw std::bad_alloc();
    // Only advice: without transparent huge pages the chunk simply uses normal pages.
    madvise(memory, kChunkBytes, MADV_HUGEPAGE);
    nodes = static_cast<DagNode*>(memory);
    m_chunks[chunk].store(nodes, std::memory_order_release);
    m_chunkCount.fetch_add(1, std::memory_order_relaxed);
    return nodes;
}

NodeId NodeArena::allocate(unsigned count) {
    std::size_t first = m_next.load(std::memory_order_relaxed);
    std::size_t start = 0;
    do {
        // Children must be consecutive and in one chunk: skip a chunk's last few ids if needed.
        start = first;
        if ((start & (kChunkNodes - 1)) + count > kChunkNodes)
            start = (start | (kChunkNodes - 1)) + 1;
        if (start + count > kBusyNode)
            throw std::length_error("Triangulator: more than 2^32 triangles in the history");
    } while (!m_next.compare_exchange_weak(first, start + count, std::memory_order_relaxed));
    // Ids skipped at the end of the previous chunk become dead nodes: a leaf with no finite
    // corner, which every traversal of the whole arena ignores.
    for (std::size_t id = first; id < start; ++id)
        new (&chunkFor(id >> kChunkBits)[id & (kChunkNodes - 1)])
            DagNode{{kNoNode, kNoNode, kNoNode}, {kNoNode, kNoNode, kNoNode}, kNoNode, 0};
    DagNode* nodes = chunkFor(start >> kChunkBits);
    for (unsigned i = 0; i < count; ++i)
        new (&nodes[(start & (kChunkNodes - 1)) + i]) DagNode{};
    return static_cast<NodeId>(start);
}

} // namespace terratin::detail

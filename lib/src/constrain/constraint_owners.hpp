#pragma once
// Which input segments each constrained edge belongs to: the segments whose chains must take
// the vertex that splits the edge (at a crossing, or a polyline point on it).

#include "../huge_pages.hpp"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace terratin::detail {

class ConstraintOwners {
public:
    using Owners = std::vector<std::uint32_t>;

    /// Room for `edges` edges without growing.
    void reserve(std::size_t edges);
    /// Adds `owners` to the edge {a, b} (either order), each at most once.
    void add(std::uint32_t a, std::uint32_t b, const Owners& owners);
    /// Removes the edge {a, b} and returns its owners (empty when it had none).
    Owners take(std::uint32_t a, std::uint32_t b);
    /// The owners of the edge {a, b} (empty when it has none), which stays.
    [[nodiscard]] Owners ownersOf(std::uint32_t a, std::uint32_t b) const;
    /// Adds every edge of `other` with its owners.
    void addAll(const ConstraintOwners& other);
    /// Whether no edge has owners here.
    [[nodiscard]] bool empty() const { return m_edges == 0; }
    /// Whether the edge {a, b} has owners here.
    [[nodiscard]] bool contains(std::uint32_t a, std::uint32_t b) const {
        return !m_slots.empty() && m_slots[slotOf(edgeKey(a, b))].key != kEmptyKey;
    }
    /// The edge {a, b} (either order) as one number: the smaller vertex in the high half.
    static std::uint64_t edgeKey(std::uint32_t a, std::uint32_t b) {
        return a < b ? (std::uint64_t{a} << 32U) | b : (std::uint64_t{b} << 32U) | a;
    }

private:
    // The edges are an open-addressing table with linear probing (an edge per insertion and
    // one lookup per split: a node-based map spent more time allocating than looking up).
    // kEmptyKey cannot be an edge's key, whose first half is the smaller vertex.
    static constexpr std::uint64_t kEmptyKey = ~std::uint64_t{0};
    // Almost every edge has one owner: each edge's owners are a list threaded through one pool
    // rather than a vector of its own (an allocation per constrained edge).
    struct Node {
        std::uint32_t owner;
        std::uint32_t next;
    };
    static constexpr std::uint32_t kEnd = 0xffffffffU;

    [[nodiscard]] std::size_t home(std::uint64_t edge) const;
    /// The slot holding `edge`, or the empty slot where it would go.
    [[nodiscard]] std::size_t slotOf(std::uint64_t edge) const;
    /// The owners of the edge in `slot` (empty for a free slot).
    [[nodiscard]] Owners ownersAt(std::size_t slot) const;
    void rehash(std::size_t slots);
    void erase(std::size_t slot);

    /// An edge's key (kEmptyKey where free) and the first node of its owners, side by side: a
    /// lookup is one cache miss.
    struct Slot {
        std::uint64_t key = kEmptyKey;
        std::uint32_t first = kEnd;
    };
    HugePageArray<Slot> m_slots; // a power of two long; megabytes read at random
    /// 64 - log2(m_slots.size()): home() keeps the hash's top bits.
    unsigned m_shift = 64;
    std::size_t m_edges = 0;
    std::vector<Node> m_nodes;
};

} // namespace terratin::detail

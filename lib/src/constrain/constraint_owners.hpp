#pragma once
// Which input segments each constrained edge belongs to: the segments whose chains must take
// the vertex that splits the edge (at a crossing, or a polyline point on it).

#include <cstddef>
#include <cstdint>
#include <unordered_map>
#include <vector>

namespace terratin::detail {

class ConstraintOwners {
public:
    using Owners = std::vector<std::uint32_t>;

    /// Room for `edges` edges without rehashing.
    void reserve(std::size_t edges) { m_first.reserve(edges); }
    /// Adds `owners` to the edge {a, b} (either order), each at most once.
    void add(std::uint32_t a, std::uint32_t b, const Owners& owners);
    /// Removes the edge {a, b} and returns its owners (empty when it had none).
    Owners take(std::uint32_t a, std::uint32_t b);

private:
    static std::uint64_t key(std::uint32_t a, std::uint32_t b) {
        return a < b ? (std::uint64_t{a} << 32U) | b : (std::uint64_t{b} << 32U) | a;
    }
    // Almost every edge has one owner: each edge's owners are a list threaded through one pool
    // rather than a vector of its own (an allocation per constrained edge).
    struct Node {
        std::uint32_t owner;
        std::uint32_t next;
    };
    static constexpr std::uint32_t kEnd = 0xffffffffU;
    std::unordered_map<std::uint64_t, std::uint32_t> m_first;
    std::vector<Node> m_nodes;
};

} // namespace terratin::detail

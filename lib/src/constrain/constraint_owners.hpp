#pragma once
// Which input segments each constrained edge belongs to. The chains of insertConstraints are
// read from it at the end (a segment's edges form a path from its first vertex to its last),
// so that splitting an edge at a crossing needs no bookkeeping in the chains themselves.

#include <cstdint>
#include <unordered_map>
#include <vector>

namespace terratin::detail {

class ConstraintOwners {
public:
    using Owners = std::vector<std::uint32_t>;

    /// Adds `owners` to the edge {a, b} (either order), each at most once.
    void add(std::uint32_t a, std::uint32_t b, const Owners& owners);
    /// Removes the edge {a, b} and returns its owners (empty when it had none).
    Owners take(std::uint32_t a, std::uint32_t b);
    /// Whether segment `owner` owns the edge {a, b}.
    [[nodiscard]] bool owns(std::uint32_t a, std::uint32_t b, std::uint32_t owner) const;
    [[nodiscard]] std::size_t edgeCount() const { return m_owners.size(); }

private:
    static std::uint64_t key(std::uint32_t a, std::uint32_t b) {
        return a < b ? (std::uint64_t{a} << 32U) | b : (std::uint64_t{b} << 32U) | a;
    }
    std::unordered_map<std::uint64_t, Owners> m_owners;
};

} // namespace terratin::detail

#pragma once
// Which input segments each constrained edge belongs to: the segments whose chains must take
// the vertex that splits the edge (at a crossing, or a polyline point on it).

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
    [[nodiscard]] std::size_t edgeCount() const { return m_owners.size(); }

private:
    static std::uint64_t key(std::uint32_t a, std::uint32_t b) {
        return a < b ? (std::uint64_t{a} << 32U) | b : (std::uint64_t{b} << 32U) | a;
    }
    std::unordered_map<std::uint64_t, Owners> m_owners;
};

} // namespace terratin::detail

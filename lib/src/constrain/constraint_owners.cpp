#include "constraint_owners.hpp"

#include <stdexcept>

namespace terratin::detail {

void ConstraintOwners::add(std::uint32_t a, std::uint32_t b, const Owners& owners) {
    std::uint32_t& first = m_first.try_emplace(key(a, b), kEnd).first->second;
    for (const std::uint32_t owner : owners) {
        bool known = false;
        for (std::uint32_t n = first; n != kEnd && !known; n = m_nodes[n].next)
            known = m_nodes[n].owner == owner;
        if (known)
            continue;
        if (m_nodes.size() >= kEnd)
            throw std::length_error("insertConstraints: too many constrained edges");
        m_nodes.push_back({owner, first});
        first = static_cast<std::uint32_t>(m_nodes.size() - 1);
    }
}

// The taken nodes stay in the pool unused: edges are taken only where they are split.
ConstraintOwners::Owners ConstraintOwners::take(std::uint32_t a, std::uint32_t b) {
    const auto found = m_first.find(key(a, b));
    if (found == m_first.end())
        return {};
    Owners owners;
    for (std::uint32_t n = found->second; n != kEnd; n = m_nodes[n].next)
        owners.push_back(m_nodes[n].owner);
    m_first.erase(found);
    return owners;
}

} // namespace terratin::detail

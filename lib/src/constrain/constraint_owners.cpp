#include "constraint_owners.hpp"

#include <algorithm>

namespace terratin::detail {

void ConstraintOwners::add(std::uint32_t a, std::uint32_t b, const Owners& owners) {
    Owners& edge = m_owners[key(a, b)];
    for (const std::uint32_t owner : owners)
        if (std::find(edge.begin(), edge.end(), owner) == edge.end())
            edge.push_back(owner);
}

ConstraintOwners::Owners ConstraintOwners::take(std::uint32_t a, std::uint32_t b) {
    const auto found = m_owners.find(key(a, b));
    if (found == m_owners.end())
        return {};
    Owners owners = std::move(found->second);
    m_owners.erase(found);
    return owners;
}

} // namespace terratin::detail

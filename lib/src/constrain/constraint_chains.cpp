#include "constraint_chains.hpp"

#include <stdexcept>

namespace terratin::detail {

void ConstraintChains::start(std::uint32_t owner, std::uint32_t a, std::uint32_t b) {
    if (m_chains.size() <= owner)
        m_chains.resize(std::size_t{owner} + 1);
    m_chains[owner] = a == b ? std::vector<std::uint32_t>{a} : std::vector<std::uint32_t>{a, b};
}

// Rounding can put two crossings within an ulp of each other, and a chain can then run to one
// and back over the same edge; every place the pair appears is split.
void ConstraintChains::insertBetween(const ConstraintOwners::Owners& owners, std::uint32_t x,
                                     std::uint32_t y, std::uint32_t w) {
    if (w == x || w == y)
        return;
    for (const std::uint32_t owner : owners) {
        std::vector<std::uint32_t>& chain = m_chains[owner];
        bool found = false;
        for (std::size_t k = 1; k < chain.size(); ++k)
            if ((chain[k - 1] == x && chain[k] == y) || (chain[k - 1] == y && chain[k] == x)) {
                chain.insert(chain.begin() + static_cast<std::ptrdiff_t>(k), w);
                found = true;
                ++k;
            }
        if (!found)
            throw std::logic_error("insertConstraints: a split edge is not on its chain");
    }
}

void ChainEdits::start(std::uint32_t owner, std::uint32_t a, std::uint32_t b) {
    m_edits.push_back({a, b, 0, static_cast<std::uint32_t>(m_owners.size()), kStart});
    m_owners.push_back(owner);
}

void ChainEdits::insertBetween(const ConstraintOwners::Owners& owners, std::uint32_t x,
                               std::uint32_t y, std::uint32_t w) {
    m_edits.push_back({x, y, w, static_cast<std::uint32_t>(m_owners.size()),
                       static_cast<std::uint32_t>(owners.size())});
    m_owners.insert(m_owners.end(), owners.begin(), owners.end());
}

void ChainEdits::applyTo(ConstraintChains& chains) {
    ConstraintOwners::Owners owners;
    for (const Edit& edit : m_edits) {
        if (edit.ownerCount == kStart) {
            chains.start(m_owners[edit.firstOwner], edit.x, edit.y);
            continue;
        }
        const auto first = m_owners.begin() + static_cast<std::ptrdiff_t>(edit.firstOwner);
        owners.assign(first, first + static_cast<std::ptrdiff_t>(edit.ownerCount));
        chains.insertBetween(owners, edit.x, edit.y, edit.w);
    }
    m_edits.clear();
    m_owners.clear();
}

} // namespace terratin::detail

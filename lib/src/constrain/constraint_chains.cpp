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

} // namespace terratin::detail

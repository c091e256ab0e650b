#include "constraint_chains.hpp"

#include <bit>
#include <stdexcept>

namespace terratin::detail {

namespace {

/// Splits noted for a chain, from entry 2 of its list on: (x, y, w) each.
constexpr std::size_t kSplitWidth = 3;

/// Up to this many splits a chain is made by scanning for each pair (short chains: no table).
constexpr std::size_t kScannedSplits = 16;

[[noreturn]] void throwNotOnChain() {
    throw std::logic_error("insertConstraints: a split edge is not on its chain");
}

// Rounding can put two crossings within an ulp of each other, and a chain can then run to one
// and back over the same edge; every place the pair appears is split.
void scanAndSplit(std::vector<std::uint32_t>& chain, std::uint32_t x, std::uint32_t y,
                  std::uint32_t w) {
    bool found = false;
    for (std::size_t k = 1; k < chain.size(); ++k)
        if ((chain[k - 1] == x && chain[k] == y) || (chain[k - 1] == y && chain[k] == x)) {
            chain.insert(chain.begin() + static_cast<std::ptrdiff_t>(k), w);
            found = true;
            ++k;
        }
    if (!found)
        throwNotOnChain();
}

/// A chain as a linked list with a table from each pair of consecutive vertices to the node
/// where it starts: a split is O(1) expected. The table is open addressing with linear probing;
/// a removed pair leaves a tombstone, and the table has twice the room of every pair ever added
/// (the first, two per split), so that probes stay short.
class LinkedChain {
public:
    LinkedChain(std::uint32_t a, std::uint32_t b, std::size_t splits)
        : m_keys(std::bit_ceil(2 * (2 * splits + 1)), kEmpty), m_at(m_keys.size()),
          m_shift(64U - static_cast<unsigned>(std::countr_zero(m_keys.size()))) {
        m_nodes.reserve(splits + 2);
        m_nodes.push_back({a, 1});
        m_nodes.push_back({b, kEnd});
        add(a, b, 0);
    }

    /// Splits the pair {x, y} at w; false, changing nothing, when the pair appears more than
    /// once (or would after the split): the table holds one place per pair.
    bool split(std::uint32_t x, std::uint32_t y, std::uint32_t w) {
        const std::size_t slot = slotOf(ConstraintOwners::edgeKey(x, y));
        if (m_keys[slot] == kEmpty)
            throwNotOnChain();
        const std::uint32_t n = m_at[slot];
        const std::uint32_t first = m_nodes[n].vertex;
        const std::uint32_t second = m_nodes[m_nodes[n].next].vertex;
        if (contains(first, w) || contains(w, second))
            return false;
        m_keys[slot] = kTombstone;
        const auto m = static_cast<std::uint32_t>(m_nodes.size());
        m_nodes.push_back({w, m_nodes[n].next});
        m_nodes[n].next = m;
        add(first, w, n);
        add(w, second, m);
        return true;
    }

    [[nodiscard]] std::vector<std::uint32_t> vertices() const {
        std::vector<std::uint32_t> chain;
        chain.reserve(m_nodes.size());
        for (std::uint32_t n = 0; n != kEnd; n = m_nodes[n].next)
            chain.push_back(m_nodes[n].vertex);
        return chain;
    }

private:
    struct Node {
        std::uint32_t vertex;
        std::uint32_t next;
    };
    static constexpr std::uint32_t kEnd = 0xffffffffU;
    // Neither can be a pair's key, whose first half is the smaller vertex.
    static constexpr std::uint64_t kEmpty = ~std::uint64_t{0};
    static constexpr std::uint64_t kTombstone = ~std::uint64_t{0} - 1;

    /// The slot holding `key`, or the empty slot where it would go.
    [[nodiscard]] std::size_t slotOf(std::uint64_t key) const {
        const std::size_t mask = m_keys.size() - 1;
        auto slot = static_cast<std::size_t>((key * 0x9e3779b97f4a7c15ULL) >> m_shift);
        while (m_keys[slot] != key && m_keys[slot] != kEmpty)
            slot = (slot + 1) & mask;
        return slot;
    }
    [[nodiscard]] bool contains(std::uint32_t a, std::uint32_t b) const {
        return m_keys[slotOf(ConstraintOwners::edgeKey(a, b))] != kEmpty;
    }
    void add(std::uint32_t a, std::uint32_t b, std::uint32_t node) {
        const std::uint64_t key = ConstraintOwners::edgeKey(a, b);
        const std::size_t slot = slotOf(key);
        m_keys[slot] = key;
        m_at[slot] = node;
    }

    std::vector<Node> m_nodes;
    std::vector<std::uint64_t> m_keys;
    std::vector<std::uint32_t> m_at;
    unsigned m_shift;
};

} // namespace

void ConstraintChains::start(std::uint32_t owner, std::uint32_t a, std::uint32_t b) {
    if (m_chains.size() <= owner)
        m_chains.resize(std::size_t{owner} + 1);
    m_chains[owner].assign({a, b});
}

void ConstraintChains::insertBetween(const ConstraintOwners::Owners& owners, std::uint32_t x,
                                     std::uint32_t y, std::uint32_t w) {
    if (w == x || w == y)
        return;
    for (const std::uint32_t owner : owners)
        m_chains[owner].insert(m_chains[owner].end(), {x, y, w});
}

std::vector<std::uint32_t> ConstraintChains::chain(std::uint32_t owner) const {
    const std::vector<std::uint32_t>& noted = m_chains[owner];
    if (noted.empty())
        return {};
    const std::uint32_t a = noted[0];
    const std::uint32_t b = noted[1];
    const std::size_t splits = (noted.size() - 2) / kSplitWidth;
    std::size_t next = 0;
    std::vector<std::uint32_t> chain;
    if (splits > kScannedSplits && a != b) {
        LinkedChain linked(a, b, splits);
        for (; next < splits; ++next) {
            const std::uint32_t* split = &noted[2 + kSplitWidth * next];
            if (!linked.split(split[0], split[1], split[2]))
                break; // a pair met twice: scanned from here on, every place split
        }
        chain = linked.vertices();
    } else {
        chain = a == b ? std::vector<std::uint32_t>{a} : std::vector<std::uint32_t>{a, b};
    }
    for (; next < splits; ++next) {
        const std::uint32_t* split = &noted[2 + kSplitWidth * next];
        scanAndSplit(chain, split[0], split[1], split[2]);
    }
    return chain;
}

void ConstraintChains::appendAfterFirst(std::uint32_t owner,
                                        std::vector<std::uint32_t>& out) const {
    const std::vector<std::uint32_t>& noted = m_chains[owner];
    if (noted.size() == 2) {
        if (noted[0] != noted[1])
            out.push_back(noted[1]);
        return;
    }
    const std::vector<std::uint32_t> whole = chain(owner);
    if (!whole.empty())
        out.insert(out.end(), whole.begin() + 1, whole.end());
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

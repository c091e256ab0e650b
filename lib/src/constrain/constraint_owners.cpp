#include "constraint_owners.hpp"

#include <algorithm>
#include <bit>
#include <stdexcept>

namespace terratin::detail {

namespace {

// At most half the slots in use keeps linear probes short.
constexpr std::size_t kSlotsPerEdge = 2;
constexpr std::size_t kMinimumSlots = 64;

} // namespace

void ConstraintOwners::reserve(std::size_t edges) {
    const std::size_t slots = std::bit_ceil(std::max(kMinimumSlots, kSlotsPerEdge * edges));
    if (slots > m_slots.size())
        rehash(slots);
    m_nodes.reserve(edges);
}

// By the edge's smaller vertex, in blocks of 8 consecutive vertices: a block's 16 slots (two
// per vertex) lie side by side at a place hashed from the block, and within 8 slots of its
// vertex's two the edge's slot is picked by a hash of the larger vertex (so that one vertex's
// edges do not share a slot). Consecutive edges of a polyline join vertices numbered one after
// another, so eight of them find their slots in a few cache lines, where a hash of the whole
// edge sends each one to a random place of a table of megabytes. The blocks lie at random
// places: a run of new vertices with more edges each than their two slots (crossings, about two
// each by their smaller end) spills from a block into the slots after it, which mostly belong to
// no block of the run. Slots by the smaller vertex alone, in order, laid such a run over one
// stretch of the table, full, and the probes ran through a cluster as long as the run: the
// crossings' insertion grew with their square.
std::size_t ConstraintOwners::home(std::uint64_t edge) const {
    constexpr std::uint64_t kGolden = 0x9e3779b97f4a7c15ULL;
    constexpr unsigned kBlockBits = 3;
    constexpr unsigned kSpreadBits = 3;
    const std::uint64_t smaller = edge >> 32U;
    const std::uint64_t block = ((smaller >> kBlockBits) * kGolden) >> m_shift;
    const std::uint64_t within = kSlotsPerEdge * (smaller & ((1U << kBlockBits) - 1U));
    const std::uint64_t spread = ((edge & 0xffffffffULL) * kGolden) >> (64U - kSpreadBits);
    return static_cast<std::size_t>((block + within + spread) & (m_slots.size() - 1));
}

std::size_t ConstraintOwners::slotOf(std::uint64_t edge) const {
    const std::size_t mask = m_slots.size() - 1;
    std::size_t slot = home(edge);
    while (m_slots[slot].key != edge && m_slots[slot].key != kEmptyKey)
        slot = (slot + 1) & mask;
    return slot;
}

void ConstraintOwners::rehash(std::size_t slots) {
    HugePageArray<Slot> old(slots);
    old.swap(m_slots);
    m_shift = 64U - static_cast<unsigned>(std::countr_zero(slots));
    for (const Slot& entry : old)
        if (entry.key != kEmptyKey)
            m_slots[slotOf(entry.key)] = entry;
}

// Backward-shift deletion: the entries after the hole that could live in it move up, so that
// every probe still reaches its key without tombstones.
void ConstraintOwners::erase(std::size_t slot) {
    const std::size_t mask = m_slots.size() - 1;
    std::size_t hole = slot;
    for (std::size_t next = (hole + 1) & mask; m_slots[next].key != kEmptyKey;
         next = (next + 1) & mask) {
        const std::size_t wanted = home(m_slots[next].key);
        // It may move to the hole when the hole lies on its probe path: from wanted to next.
        if (((next - wanted) & mask) >= ((next - hole) & mask)) {
            m_slots[hole] = m_slots[next];
            hole = next;
        }
    }
    m_slots[hole] = Slot{};
    --m_edges;
}

void ConstraintOwners::add(std::uint32_t a, std::uint32_t b, const Owners& owners) {
    if (kSlotsPerEdge * (m_edges + 1) > m_slots.size())
        rehash(std::max(kMinimumSlots, 2 * m_slots.size()));
    const std::uint64_t edge = edgeKey(a, b);
    Slot& slot = m_slots[slotOf(edge)];
    if (slot.key == kEmptyKey) {
        slot = {edge, kEnd};
        ++m_edges;
    }
    std::uint32_t& first = slot.first;
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
    if (m_slots.empty())
        return {};
    const std::size_t slot = slotOf(edgeKey(a, b));
    Owners owners = ownersAt(slot);
    if (m_slots[slot].key != kEmptyKey)
        erase(slot);
    return owners;
}

ConstraintOwners::Owners ConstraintOwners::ownersOf(std::uint32_t a, std::uint32_t b) const {
    if (m_slots.empty())
        return {};
    return ownersAt(slotOf(edgeKey(a, b)));
}

ConstraintOwners::Owners ConstraintOwners::ownersAt(std::size_t slot) const {
    Owners owners;
    if (m_slots[slot].key == kEmptyKey)
        return owners;
    for (std::uint32_t n = m_slots[slot].first; n != kEnd; n = m_nodes[n].next)
        owners.push_back(m_nodes[n].owner);
    return owners;
}

void ConstraintOwners::addAll(const ConstraintOwners& other) {
    Owners owners;
    for (const Slot& slot : other.m_slots) {
        if (slot.key == kEmptyKey)
            continue;
        owners.clear();
        for (std::uint32_t n = slot.first; n != kEnd; n = other.m_nodes[n].next)
            owners.push_back(other.m_nodes[n].owner);
        add(static_cast<std::uint32_t>(slot.key >> 32U), static_cast<std::uint32_t>(slot.key),
            owners);
    }
}

} // namespace terratin::detail

#pragma once
// The chain of vertices each input segment becomes: a segment starts as its two ends, and every
// vertex that splits one of its edges (a vertex on it, a crossing, a point on a constrained edge)
// goes between that edge's two vertices. The splits are noted as they come and made when the
// chain is asked for, through a table from each pair of consecutive vertices to its place.

#include "cdt_mesh.hpp"
#include "constraint_owners.hpp"

#include <cstdint>
#include <vector>

namespace terratin::detail {

class ConstraintChains {
public:
    /// Segment `owner` (numbered from 0 without gaps) from a to b: the chain (a, b), or (a)
    /// when a == b.
    void start(std::uint32_t owner, std::uint32_t a, std::uint32_t b);

    /// Puts `w` between x and y wherever they are consecutive (either order) in the chain of
    /// each of `owners`; nothing when w is x or y. O(1) per owner: the split is noted, and
    /// chain() makes the splits in order.
    void insertBetween(const ConstraintOwners::Owners& owners, std::uint32_t x, std::uint32_t y,
                       std::uint32_t w);

    /// Segment `owner`'s chain: its start with every split noted since made in order. Throws
    /// std::logic_error when a split's pair is not consecutive in the chain by then (a broken
    /// invariant). O(splits) expected.
    [[nodiscard]] std::vector<std::uint32_t> chain(std::uint32_t owner) const;
    /// Appends chain(owner) less its first vertex to `out` (a polyline's chain is its segments'
    /// chains joined); an unsplit chain without a copy.
    void appendAfterFirst(std::uint32_t owner, std::vector<std::uint32_t>& out) const;

    /// Room for segments 0 to `segments` - 1: start() then grows nothing, and may be called
    /// for different segments at once.
    void prepare(std::size_t segments) {
        if (m_chains.size() < segments)
            m_chains.resize(segments);
    }

    /// Replaces every vertex v >= `kept` of every chain by movedTo[v - kept]
    /// (CdtMesh::compact).
    void renumber(std::size_t kept, const std::vector<std::uint32_t>& movedTo) {
        renumberMoved(m_chains, kept, movedTo);
    }

private:
    /// Per segment: its two ends (the same vertex twice for a chain of one), then a triple
    /// (x, y, w) per split. A chain stored as its vertices would make a split O(chain
    /// length), to find the pair and to open a place for w; a segment that many others cross
    /// would then cost the square of its crossings. Each segment's list is its own, so
    /// different segments may be started and split at once.
    std::vector<std::vector<std::uint32_t>> m_chains;
};

/// start() and insertBetween() calls kept to be made on a ConstraintChains later, in the same
/// order. A zone's inserter keeps them (ConstraintInserter::absorb makes them): two zones may
/// split different edges of one earlier segment's chain at once, and the chain is one vector.
/// Splits of different edges commute, so the chains end the same as if made at once.
class ChainEdits {
public:
    void start(std::uint32_t owner, std::uint32_t a, std::uint32_t b);
    void insertBetween(const ConstraintOwners::Owners& owners, std::uint32_t x, std::uint32_t y,
                       std::uint32_t w);
    /// Makes the calls on `chains`, in order, and forgets them.
    void applyTo(ConstraintChains& chains);

private:
    /// A start (ownerCount kStart, the owner in m_owners[firstOwner]) or a split of x -> y at
    /// w for the ownerCount owners from m_owners[firstOwner]: a pool, not a vector per edit.
    static constexpr std::uint32_t kStart = 0xffffffffU;
    struct Edit {
        std::uint32_t x;
        std::uint32_t y;
        std::uint32_t w;
        std::uint32_t firstOwner;
        std::uint32_t ownerCount;
    };
    std::vector<Edit> m_edits;
    std::vector<std::uint32_t> m_owners;
};

} // namespace terratin::detail

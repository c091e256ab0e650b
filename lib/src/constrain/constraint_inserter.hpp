#pragma once
// The state of one insertConstraints call: the mutable mesh, the owners of constrained edges,
// and the pieces of segments still to insert.

#include "cdt_mesh.hpp"
#include "constraint_chains.hpp"
#include "constraint_owners.hpp"
#include "insertion_poll.hpp"
#include "segment_cavity.hpp"
#include "segment_flips.hpp"
#include "terratin/constrain/constrained_tin.hpp"
#include "terratin/geometry/point.hpp"
#include "vertex_buckets.hpp"

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <set>
#include <span>
#include <unordered_set>
#include <vector>

namespace terratin::detail {

class ConstraintInserter {
public:
    /// `segments`: how many segments will be inserted (to size the tables).
    ConstraintInserter(TinMesh mesh, std::size_t segments)
        : m_mesh(std::move(mesh)), m_segmentCount(segments) {
        m_owners.reserve(2 * segments);
    }
    /// An inserter for one zone of `shared`'s mesh (CdtMesh's views), with the slots it may
    /// fill; about `segments` segments go in through it. Its operations throw ZoneRefusal,
    /// changing nothing, when they would reach outside the zone: after one in insertSegment,
    /// takePieces() gives what is left of that segment. Only inserters of disjoint zones may
    /// work at once. It reads `shared`'s owners (an earlier round's edges) without changing
    /// them, nor then the chains: absorb() makes its changes to both.
    ConstraintInserter(ConstraintInserter& shared, Zone zone, SlotRange vertices,
                       SlotRange triangles, std::size_t segments)
        : m_mesh(shared.m_mesh, zone, vertices, triangles), m_chains(shared.m_chains),
          m_sharedOwners(&shared.m_owners), m_deferChains(!shared.m_owners.empty()),
          m_segmentCount(segments) {
        m_owners.reserve(2 * segments);
    }
    ConstraintInserter(const ConstraintInserter&) = delete;
    ConstraintInserter& operator=(const ConstraintInserter&) = delete;

    /// From now on every point and every piece of a segment is a step of `poll`, whose check
    /// may throw to stop the insertion (insertion_poll.hpp).
    void setPoll(InsertionPoll poll) { m_poll = std::move(poll); }
    /// The share of the segments given to the constructor that have gone in, here and in the
    /// zones absorbed (0 to 1).
    [[nodiscard]] double fractionInserted() const {
        return m_segmentCount == 0
                   ? 1.0
                   : static_cast<double>(m_segmentsInserted) / static_cast<double>(m_segmentCount);
    }

    /// The vertex at `p`'s x and y: an existing one, or a new one (sourceIndex
    /// kConstraintPointSource); nothing when `p` lies outside the convex hull. The search
    /// starts near the previous point, or anywhere when `jump` (the first point of a polyline).
    std::optional<std::uint32_t> insertPoint(const Point3& p, bool jump);
    /// insertPoint, the search starting from `triangle` (any triangle index of the mesh).
    std::optional<std::uint32_t> insertPointFrom(const Point3& p, std::size_t triangle);

    /// Makes the segment a -> b of input segment `owner` a chain of constrained edges,
    /// splitting it (and what it crosses) where needed.
    void insertSegment(std::uint32_t a, std::uint32_t b, std::uint32_t owner);

    /// What is left of a segment: pieces still to insert, each between two vertices, with the
    /// input segments they belong to.
    struct Piece {
        std::uint32_t from;
        std::uint32_t to;
        ConstraintOwners::Owners owners;
    };
    /// After a ZoneRefusal from insertSegment: the pieces of that segment not inserted yet.
    [[nodiscard]] std::vector<Piece> takePieces() { return std::move(m_pieces); }
    /// Inserts pieces that another inserter's zone refused (takePieces), as insertSegment
    /// would have gone on.
    void insertPieces(std::vector<Piece> pieces);

    /// Room in the chains for `segments` segments: a zone's inserters may then start theirs
    /// at once.
    void prepareChains(std::size_t segments) { m_chains->prepare(segments); }
    /// Takes over what a zone's inserter did: its constrained edges' owners (those of earlier
    /// edges it split removed), its chains' starts and splits, its counts, and the flips its
    /// zone's edge left (made now). Call after every zone is done, in the zones' order.
    void absorb(ConstraintInserter& zone);
    /// Closes up the slots the zones left unused (CdtMesh::compact) and renumbers the vertices
    /// of the chains and of `vertexLists` to match.
    void compact(std::span<const SlotRange> unusedVertices,
                 std::span<const SlotRange> unusedTriangles,
                 std::vector<std::vector<std::uint32_t>>& vertexLists);
    /// The view's slots as far as it used them.
    [[nodiscard]] SlotRange vertexSlots() const { return m_mesh.vertexSlots(); }
    [[nodiscard]] SlotRange triangleSlots() const { return m_mesh.triangleSlots(); }
    /// appendSlots of the mesh.
    std::pair<SlotRange, SlotRange> appendSlots(std::size_t vertices, std::size_t triangles) {
        return m_mesh.appendSlots(vertices, triangles);
    }
    /// The mesh (a zone's view: its zone's part is read safely).
    [[nodiscard]] CdtMesh& mesh() { return m_mesh; }

    /// The vertices of segment `owner`'s chain, from its first vertex to its last (final once
    /// every segment is inserted).
    [[nodiscard]] std::vector<std::uint32_t> chainOf(std::uint32_t owner) const {
        return m_chains->chain(owner);
    }
    /// Appends chainOf(owner) less its first vertex to `out`.
    void appendChainAfterFirst(std::uint32_t owner, std::vector<std::uint32_t>& out) const {
        m_chains->appendAfterFirst(owner, out);
    }

    /// Moves the mesh and the flags into `tin`, with the counts of added vertices.
    void finish(ConstrainedTin& tin);

private:
    /// Runs the pieces on m_pieces until none is left.
    void insertPendingPieces(std::uint32_t owner);
    /// Inserts `piece`, moving its start along as its parts go in.
    void insertPiece(Piece& piece);
    void markConstrained(std::size_t h, const ConstraintOwners::Owners& owners);
    /// For a zone's inserter: throws ZoneRefusal unless both ends of the constrained edge
    /// {a, b} lie in the zone, which then alone may change its flags and owners.
    void requireEdgeInZone(std::uint32_t a, std::uint32_t b) const;
    /// Removes the constrained edge {a, b} and returns its owners: for a zone's inserter, those
    /// it gave the edge and, the first time, those of an earlier round (kept in the shared
    /// owners until absorb).
    ConstraintOwners::Owners takeOwners(std::uint32_t a, std::uint32_t b);
    /// ConstraintChains::start and insertBetween on the chains, or for a zone's inserter kept
    /// for absorb.
    void startChain(std::uint32_t owner, std::uint32_t a, std::uint32_t b);
    void splitChains(const ConstraintOwners::Owners& owners, std::uint32_t x, std::uint32_t y,
                     std::uint32_t w);
    void splitAtCrossing(std::uint32_t u, std::uint32_t v, const ConstraintOwners::Owners& owners,
                         std::size_t crossed);
    /// The vertex at `crossing`, where u -> v crosses the constrained edge of half-edge
    /// `crossed`: one at it or within rounding of it, else none yet (`where` then says where
    /// it goes, checked insertable in this inserter's zone).
    std::optional<std::uint32_t> crossingVertex(const Point3& crossing, std::size_t crossed,
                                                MeshLocation& where);
    [[nodiscard]] std::optional<std::uint32_t> vertexWithinRounding(const Point3& p,
                                                                    std::size_t triangle) const;
    [[nodiscard]] std::optional<std::uint32_t> nearEndpoint(std::uint32_t u, std::uint32_t v,
                                                            std::uint32_t c, std::uint32_t d,
                                                            double sideC, double sideD) const;
    std::uint32_t insertVertex(const Point3& p, std::uint32_t source, const MeshLocation& where);

    CdtMesh m_mesh;
    ConstraintOwners m_owners;
    ConstraintChains m_ownChains;
    ConstraintChains* m_chains = &m_ownChains; // a zone's inserter: the shared one's
    /// A zone's inserter: the shared inserter's owners (an earlier round's edges), read only;
    /// the earlier edges it split (ConstraintOwners::edgeKey); and its chains' changes, for
    /// absorb.
    const ConstraintOwners* m_sharedOwners = nullptr;
    std::unordered_set<std::uint64_t> m_takenShared;
    /// Whether the chains' edits wait for absorb: when there are earlier edges, whose
    /// segments' chains another zone may split too. Without, each zone changes only the chains
    /// of its own segments, at once.
    bool m_deferChains = false;
    ChainEdits m_chainEdits;
    std::vector<Piece> m_pieces;
    /// The crossings (u, v, c, d) met while inserting the current segment: one met again means
    /// that rounding sends the pieces round in a circle (see splitAtCrossing).
    std::set<std::array<std::uint32_t, 4>> m_crossingsMet;
    CrossedEdges m_crossed;
    CavityScratch m_cavity;
    std::optional<VertexBuckets> m_buckets; // built for the first polyline
    std::size_t m_hintTriangle = 0;
    std::size_t m_addedPoints = 0;
    std::size_t m_intersections = 0;
    InsertionPoll m_poll;
    std::size_t m_segmentCount = 0;
    std::size_t m_segmentsInserted = 0;
};

} // namespace terratin::detail

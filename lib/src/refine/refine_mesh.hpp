#pragma once
/// @file
/// The refiner's triangulation: a Delaunay triangulation of the chosen cells kept in place,
/// without a history.
///
/// Refinement needs no point location from scratch: every point inserted is a candidate
/// cell, found by scanning a known triangle, so a short walk from that triangle finds it.
/// A DAG would keep every triangle ever made (several times the live ones, most of the
/// memory the refiner touches); here an insertion's cavity slots are reused at once, so the
/// triangles in use stay dense and in cache. A slot's version changes with every edit, which
/// is how a queued candidate knows that its triangle is gone.
///
/// The TIN starts as the convex hull of the valid cells (strictly convex), triangulated and
/// made Delaunay, so every later point lies inside it or on its boundary: no auxiliary
/// triangle or symbolic point is needed. Insertion is Bowyer-Watson's: the cavity is every
/// triangle whose circumcircle strictly contains the point (exact predicates), replaced by a
/// fan from the point. Cocircular points (every 2 x 2 block of a grid) keep whichever
/// diagonal came first, so the TIN depends on the order of insertions only.
///
/// Strips: every vertex belongs to a strip (the refiner's vertical bands of the raster), and
/// a triangle spans the strips from its corners' lowest to their highest. An insertion
/// restricted to a range of strips touches only triangles within it; it gives up, changing
/// nothing, when its walk or cavity reaches another triangle. Its new triangles have the point
/// and cavity corners as corners, so they lie within the range too. Neighbours outside the
/// cavity get one link rewritten, the one facing it, found from their corners (which never
/// change while they are outside every cavity): insertions restricted to disjoint ranges may
/// run at once. New slots come from regions (the refiner has one per strip), each used by
/// one thread at a time.
///
/// Why not the triangulator's CavityMesh (cavity_mesh.hpp), also a restricted Bowyer-Watson
/// core: the two differ where each is fast. The refiner starts from the hull, so it needs no
/// ghost triangles; it needs what the triangulator would pay for and never use: a version per
/// slot for its lazy candidates, a range of strips per triangle (its tasks are strips and
/// pairs of strips, and a refusal says which range it needed), vertices that carry their
/// pixel for the scans, and a cap on the triangles an insertion adds (the triangle limit).
/// CavityMesh covers the plane with ghosts (points come in any order), labels a triangle with
/// one owner strip and merges strips by levels, and keeps 24-byte triangles whose links name
/// the corner across. One core would make one of them carry the other's fields per triangle.

#include "../huge_pages.hpp"
#include "../mesh/node_arena.hpp"

#include "terratin/geometry/point.hpp"
#include "terratin/triangulate/tin_mesh.hpp"

#include <array>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

namespace terratin::detail {

using TriId = std::uint32_t;
inline constexpr TriId kNoTriangle = 0xFFFFFFFFU;

/// Strips first to last, inclusive: the strips a triangle spans, or those an insertion may
/// touch.
struct StripRange {
    std::uint8_t first = 0;
    std::uint8_t last = 0;

    static constexpr StripRange all() { return {0, 0xFF}; }
    [[nodiscard]] bool contains(StripRange other) const {
        return first <= other.first && other.last <= last;
    }
    [[nodiscard]] bool single() const { return first == last; }
    friend bool operator==(StripRange a, StripRange b) = default;
};

/// A vertex as the mesh and the refiner keep it, half a cache line: an insertion reads the
/// positions and strips of its cavity's corners, and the scans that follow read the pixels of
/// the same corners.
struct RefineVertex {
    /// Where the vertex lies in the TIN.
    Point2 position;
    /// Its cell in pixel coordinates, and the cell's elevation.
    std::int32_t col;
    std::int32_t row;
    float z;
    std::uint8_t strip;
};
static_assert(sizeof(RefineVertex) == 32);

/// A triangle of the refiner's mesh; v counter-clockwise, n[i] across the edge opposite v[i]
/// (kNoTriangle on the hull).
struct MeshTriangle {
    std::array<VertexId, 3> v;
    std::array<TriId, 3> n;
    /// Changed with every edit of the slot (read through RefineMesh::version).
    std::uint32_t version;
    /// The strips of its corners, lowest to highest.
    StripRange strips;

    /// The edge (0..2) across which `neighbour` lies; it must be one of n.
    [[nodiscard]] int edgeTowards(TriId neighbour) const {
        int e = 0;
        while (n[static_cast<std::size_t>(e)] != neighbour)
            ++e;
        return e;
    }
};

class RefineMesh {
public:
    /// What tryInsert needs besides the mesh, one per inserting thread.
    struct InsertScratch {
        /// The edge (a, b) of the cavity's boundary, counter-clockwise seen from inside, and
        /// the triangle beyond it.
        struct Edge {
            VertexId a;
            VertexId b;
            TriId beyond;
        };
        std::vector<TriId> cavity;
        std::vector<Edge> boundary;
        /// After a successful tryInsert: the new triangles, all with the point as a corner.
        std::vector<TriId> fan;
        /// After one refused for its strips: `allowed` widened by the triangle it met.
        StripRange needed;
    };

    /// `vertices` are read as they are used (positions and strips); `capacity` bounds the
    /// slots of all regions together.
    RefineMesh(std::span<const RefineVertex> vertices, std::size_t capacity);

    /// Reserves the next `slots` slots as a region and returns its index. Call before the
    /// region is used, never while insertions run.
    unsigned addRegion(std::size_t slots);

    /// Triangulates the strictly convex counter-clockwise polygon `hull` and makes it
    /// Delaunay, in slots of `region`. Must be called once, first.
    void startFromHull(std::span<const VertexId> hull, unsigned region);

    [[nodiscard]] const MeshTriangle& triangle(TriId t) const { return m_triangles[t]; }
    [[nodiscard]] StripRange strips(TriId t) const { return m_triangles[t].strips; }
    /// May be read while another thread edits the slot (a candidate's triangle taken over by
    /// another strip): atomic, unlike the rest of the triangle.
    [[nodiscard]] std::uint32_t version(TriId t) const {
        return std::atomic_ref<std::uint32_t>(m_triangles[t].version)
            .load(std::memory_order_acquire);
    }
    [[nodiscard]] bool inUse(TriId t) const { return m_triangles[t].v[0] != kNoVertex; }
    /// The slots in use, region by region: the order of extract()'s triangles.
    [[nodiscard]] std::vector<TriId> slotsInUse() const;
    /// One past the highest slot handed out.
    [[nodiscard]] TriId slotEnd() const;

    /// The triangle holding q (inside or on its boundary), walking from `start`.
    [[nodiscard]] TriId walk(const Point2& q, TriId start) const;

    /// Inserts p, walking from `start`, and leaves its new triangles in scratch.fan; new slots
    /// come from `region`. Returns 0 and changes nothing when the walk or the cavity meets a
    /// triangle not within `allowed` (then scratch.needed is the range the insertion needs, as
    /// far as it went) or when it would add more than `maxAdded` triangles. Returns the number
    /// of triangles added: 2, or 1 on a hull edge.
    int tryInsert(VertexId p, TriId start, StripRange allowed, unsigned region,
                  InsertScratch& scratch, int maxAdded = 2);

    /// The triangles in use, in slotsInUse() order, with neighbours as indices into it; on up
    /// to `threads` threads.
    void extract(MeshArray<std::uint32_t>& triangles, MeshArray<std::int32_t>& neighbours,
                 unsigned threads = 1) const;
    /// Bytes of the slots handed out (the reserved capacity beyond is untouched).
    [[nodiscard]] std::size_t memoryBytes() const;

private:
    static constexpr VertexId kNoVertex = 0xFFFFFFFFU;

    /// A range of slots one thread at a time takes from; cache-line aligned, as the threads
    /// advance their own `next` at once.
    struct alignas(64) Region {
        TriId begin = 0;
        TriId next = 0;
        TriId end = 0;
    };

    TriId allocate(unsigned region);
    /// The edge of t (by its opposite corner) with q strictly beyond it, or -1 when t holds q
    /// (inside or on its boundary): a walk's next step.
    [[nodiscard]] int exitEdge(TriId t, const Point2& q) const;
    void set(TriId t, std::array<VertexId, 3> v, std::array<TriId, 3> n);
    /// In triangle `in` (outside every cavity), points the link across its edge (a, b) at `to`.
    void relinkAcross(TriId in, VertexId a, VertexId b, TriId to);
    /// In triangle `in`, points the link that pointed to `from` at `to` (the hull's flips).
    void relink(TriId in, TriId from, TriId to);
    /// Flips the edge of t opposite corner e when the point beyond it is strictly inside t's
    /// circumcircle (the hull's triangulation). Returns the neighbour, or kNoTriangle when
    /// nothing was flipped.
    TriId flipIfIllegal(TriId t, int e);
    [[nodiscard]] const Point2& point(VertexId v) const { return m_vertices[v].position; }

    /// tryInsert's steps. The walk from `start` to the triangle holding q, kNoTriangle when it
    /// meets one not within `allowed`; the cavity of q from that triangle into scratch.cavity
    /// and its boundary into scratch.boundary, false when it meets one not within `allowed`
    /// (either way scratch.needed is then set, refuse); the fan of p over the boundary, in the
    /// cavity's slots and then new ones of `region`, into scratch.fan, linked to the triangles
    /// beyond.
    [[nodiscard]] TriId walkWithin(const Point2& q, TriId start, StripRange allowed,
                                   InsertScratch& scratch) const;
    [[nodiscard]] bool findCavity(const Point2& q, TriId t, StripRange allowed,
                                  InsertScratch& scratch) const;
    void makeFan(VertexId p, unsigned region, InsertScratch& scratch);
    /// scratch.needed for an insertion within `allowed` that met triangle `met`.
    void refuse(TriId met, StripRange allowed, InsertScratch& scratch) const;
    /// Asks for the records of the neighbours of `t`, which a cavity search reads next.
    void requestNeighbours(TriId t) const;

    std::span<const RefineVertex> m_vertices;
    std::size_t m_capacity = 0;
    HugePageBuffer<MeshTriangle> m_triangles;
    std::vector<Region> m_regions;
};

} // namespace terratin::detail

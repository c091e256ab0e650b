#pragma once
/// @file
/// The refiner's triangulation: a Delaunay triangulation of the chosen cells kept in place,
/// without a history.
///
/// Refinement needs no point location from scratch: every point inserted is a candidate
/// cell, found by scanning a known triangle, so a short walk from that triangle finds it.
/// A DAG would keep every triangle ever made (several times the live ones, most of the
/// memory the refiner touches); here a split or flipped triangle's slot is reused at once,
/// so the triangles in use stay dense and in cache. A slot's version changes with every
/// edit, which is how a queued candidate knows that its triangle is gone.
///
/// The TIN starts as the convex hull of the valid cells (strictly convex), triangulated and
/// made Delaunay, so every later point lies inside it or on its boundary: no auxiliary
/// triangle or symbolic point is needed. Predicates are exact; an edge is flipped only when
/// the opposite point is strictly inside the circumcircle, so cocircular points (every 2 x 2
/// block of a grid) keep whichever diagonal came first. That choice depends only on the
/// order of insertions, and the refiner's rounds insert the same points in the same order for
/// any thread count.
///
/// Concurrency: insert() may run from several threads on triangles that do not meet (the
/// refiner's zones); each thread takes new slots from a block of its own. version() may be
/// read while others insert.

#include "../triangulate/node_arena.hpp"

#include "terratin/geometry/point.hpp"
#include "terratin/huge_pages.hpp"

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

/// A triangle of the refiner's mesh; v counter-clockwise, n[i] across the edge opposite v[i]
/// (kNoTriangle on the hull).
struct MeshTriangle {
    std::array<VertexId, 3> v;
    std::array<TriId, 3> n;
    /// Changed with every edit of the slot (read through RefineMesh::version).
    std::uint32_t version;
    /// The refiner's claim stamp (its accept loop, one thread).
    std::uint32_t owner;
};

class RefineMesh {
public:
    /// A thread's working state for insert(): its block of free slots and its flip stack.
    struct Scratch {
        TriId next = 0;
        TriId end = 0;
        std::vector<std::pair<TriId, int>> pending;
    };

    /// `points` are read as vertices are used; `maxTriangles` bounds the triangles ever in
    /// use and `threads` the threads inserting at once (for the slot blocks).
    RefineMesh(std::span<const Point2> points, std::size_t maxTriangles, unsigned threads);

    /// Triangulates the strictly convex counter-clockwise polygon `hull` and makes it
    /// Delaunay. Must be called once, first.
    void startFromHull(std::span<const VertexId> hull);

    [[nodiscard]] const MeshTriangle& triangle(TriId t) const { return m_triangles[t]; }
    [[nodiscard]] std::uint32_t& owner(TriId t) { return m_triangles[t].owner; }
    [[nodiscard]] std::uint32_t owner(TriId t) const { return m_triangles[t].owner; }
    [[nodiscard]] std::uint32_t version(TriId t) const {
        return std::atomic_ref<std::uint32_t>(m_triangles[t].version)
            .load(std::memory_order_acquire);
    }
    /// Slots handed out so far (some may be unused: see extract).
    [[nodiscard]] TriId slotCount() const { return m_nextSlot.load(std::memory_order_relaxed); }
    [[nodiscard]] bool inUse(TriId t) const { return m_triangles[t].v[0] != kNoVertex; }

    /// The triangle holding point p (inside or on its boundary), walking from `start`.
    [[nodiscard]] TriId walk(VertexId p, TriId start) const;
    /// The corner opposite the edge of t that p lies on, or -1 when p is inside t.
    [[nodiscard]] int edgeContaining(TriId t, VertexId p) const;
    /// Inserts p, which t holds, restores the Delaunay property and appends the triangles
    /// around p to `fan`. Returns the number of triangles added: 2, or 1 on the hull.
    int insert(VertexId p, TriId t, Scratch& scratch, std::vector<TriId>& fan);

    /// The triangles in use, in slot order, with neighbours as indices into that order.
    void extract(std::vector<std::uint32_t>& triangles, std::vector<std::int32_t>& neighbours) const;
    /// Bytes of the slots handed out (the reserved capacity beyond is untouched).
    [[nodiscard]] std::size_t memoryBytes() const { return slotCount() * sizeof(MeshTriangle); }

private:
    static constexpr VertexId kNoVertex = 0xFFFFFFFFU;

    TriId allocate(Scratch& scratch);
    void set(TriId t, std::array<VertexId, 3> v, std::array<TriId, 3> n);
    /// In triangle `in`, points the link that pointed to `from` at `to`.
    void relink(TriId in, TriId from, TriId to);
    /// Lawson's flips for the edges queued in scratch.pending (each opposite p, at v[0]).
    void legalize(Scratch& scratch);
    /// Flips the edge of t opposite corner e when the point beyond it is strictly inside t's
    /// circumcircle. Afterwards t = (p, x, d) and the neighbour = (p, d, y), p being t's corner
    /// e, x and y the edge's ends and d the point beyond. Returns the neighbour, or
    /// kNoTriangle when nothing was flipped.
    TriId flipIfIllegal(TriId t, int e);
    [[nodiscard]] const Point2& point(VertexId v) const { return m_points[v]; }

    std::span<const Point2> m_points;
    std::size_t m_capacity = 0;
    HugePageBuffer<MeshTriangle> m_triangles;
    std::atomic<TriId> m_nextSlot{0};
};

} // namespace terratin::detail

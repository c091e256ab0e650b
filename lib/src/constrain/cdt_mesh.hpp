#pragma once
// The mutable triangulation behind insertConstraints: TinMesh's flat arrays plus a constrained
// flag per half-edge and one incident triangle per vertex, with the local operations
// (location, point insertion, flips) that keep it constrained Delaunay.
//
// Notation: half-edge h = 3t + i runs from corner i to corner (i+1)%3 of triangle t; its twin
// is the half-edge of the neighbour across that edge, running the other way.
//
// Zones: several threads may change one mesh at once, each through a view of its own that is
// confined to a zone, a band [low, high) of x or of y. A view owns the triangles whose three
// corners lie in its zone; it rewrites only those, and reads a triangle or a link only across an
// edge with an end in its zone. Another zone's view writes only its own triangles and the links and
// flags of edges with both ends in its zone, so the two never touch the same data. An operation
// that would need more throws ZoneRefusal before it writes anything; a flip it would need across
// the zone's edge is left undone and listed (takePending), for the mesh's owner to make once the
// views are done. New vertices and triangles go to slots reserved for the view (appendSlots),
// closed up afterwards (compact). docs/algorithms.md has the proof.

#include "terratin/geometry/point.hpp"
#include "terratin/triangulate/tin_mesh.hpp"

#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <memory>
#include <span>
#include <utility>
#include <vector>

namespace terratin::detail {

inline constexpr std::size_t kNoHalfEdge = std::numeric_limits<std::size_t>::max();

inline std::size_t nextHalfEdge(std::size_t h) {
    return h % 3 == 2 ? h - 2 : h + 1;
}
inline std::size_t previousHalfEdge(std::size_t h) {
    return h % 3 == 0 ? h + 2 : h - 1;
}

/// Thrown by a zone's view before an operation writes anything, when the operation would reach
/// outside the zone or the view's reserved slots are used up.
struct ZoneRefusal {};

/// A band of the plane: low <= x < high, or with `alongY` low <= y < high.
struct Zone {
    bool alongY = false;
    double low = 0.0;
    double high = 0.0;

    [[nodiscard]] bool holds(const Point3& p) const {
        const double coordinate = alongY ? p.y : p.x;
        return coordinate >= low && coordinate < high;
    }
};

/// `zones` bands of x (or of y, `alongY`) covering the plane, holding about as many of
/// `coordinates` (the x or the y of what goes into them) each.
[[nodiscard]] std::vector<Zone> bandsHoldingAsMany(std::vector<double> coordinates, unsigned zones,
                                                   bool alongY);

/// Replaces every vertex v >= `kept` in `lists` by movedTo[v - kept] (CdtMesh::compact).
void renumberMoved(std::span<std::vector<std::uint32_t>> lists, std::size_t kept,
                   std::span<const std::uint32_t> movedTo);

/// Slots of the mesh's arrays reserved up to `end`, the next free one at `next`.
struct SlotRange {
    std::size_t next = 0;
    std::size_t end = 0;
};

/// Where a point lies in the triangulation.
struct MeshLocation {
    enum class Kind { InTriangle, OnEdge, OnVertex, OutsideHull };
    Kind kind = Kind::OutsideHull;
    /// InTriangle: a half-edge of the triangle; OnEdge: the half-edge the point lies on.
    std::size_t halfEdge = kNoHalfEdge;
    /// OnVertex: the vertex.
    std::uint32_t vertex = 0;
};

class CdtMesh {
public:
    /// Takes the arrays of a valid triangulation.
    explicit CdtMesh(TinMesh mesh);
    /// The same, with the constrained flags of a constrained triangulation (one per half-edge).
    CdtMesh(TinMesh mesh, MeshArray<std::uint8_t> constrained);
    /// A view of `shared`'s arrays confined to `zone`, its new vertices and triangles taken
    /// from `vertices` and `triangles` (appendSlots). `shared` must outlive it; only views of
    /// disjoint zones may work at once, and `shared` itself only when none does.
    CdtMesh(CdtMesh& shared, Zone zone, SlotRange vertices, SlotRange triangles);

    /// Appends `vertices` vertex slots and `triangles` triangle slots that nothing uses, and
    /// returns them; compact() removes those left unused.
    std::pair<SlotRange, SlotRange> appendSlots(std::size_t vertices, std::size_t triangles);
    /// Removes the slots of `unusedVertices` and `unusedTriangles` (ranges [next, end) of each,
    /// disjoint), which nothing refers to, by moving the last vertices and triangles into them:
    /// O(slots removed) with the degree of each vertex moved. Returns where the vertices moved:
    /// vertex v >= the new vertexCount() is now movedTo[v - vertexCount()]; the others stay.
    /// A moved triangle takes its recordWrites mark along.
    std::vector<std::uint32_t> compact(std::span<const SlotRange> unusedVertices,
                                       std::span<const SlotRange> unusedTriangles);
    /// The view's slots as far as it used them.
    [[nodiscard]] SlotRange vertexSlots() const { return m_vertexSlots; }
    [[nodiscard]] SlotRange triangleSlots() const { return m_triangleSlots; }
    /// Whether vertex `v` lies in the view's zone (every vertex when the mesh is no view).
    [[nodiscard]] bool inZone(std::uint32_t v) const {
        return !m_zoned || m_zone.holds(m_arrays->mesh.vertices[v]);
    }
    /// Whether this is a zone's view.
    [[nodiscard]] bool isView() const { return m_zoned; }
    /// Whether the view owns triangle t: its three corners in the zone.
    [[nodiscard]] bool owns(std::size_t t) const {
        return inZone(from(3 * t)) && inZone(from(3 * t + 1)) && inZone(from(3 * t + 2));
    }
    /// Throws ZoneRefusal unless the view owns triangle t.
    void requireOwned(std::size_t t) const {
        if (!owns(t))
            throw ZoneRefusal{};
    }
    /// Throws ZoneRefusal unless a view owns what inserting a point at `where` rewrites and
    /// has a vertex and two triangles left.
    void requireInsertable(const MeshLocation& where) const;
    /// Throws ZoneRefusal unless the view may read across half-edge h: one of its ends in the
    /// zone.
    void requireCrossable(std::size_t h) const {
        if (!inZone(from(h)) && !inZone(to(h)))
            throw ZoneRefusal{};
    }

    /// From now on, sets (*written)[t] = 1 for every triangle t written (growing it as
    /// triangles are added); nullptr stops.
    void recordWrites(std::vector<std::uint8_t>* written) { m_written = written; }

    [[nodiscard]] const TinMesh& mesh() const { return m_arrays->mesh; }
    [[nodiscard]] TinMesh takeMesh() { return std::move(m_arrays->mesh); }
    [[nodiscard]] MeshArray<std::uint8_t> takeFlags() { return std::move(m_arrays->constrained); }

    [[nodiscard]] std::size_t vertexCount() const { return m_arrays->mesh.vertices.size(); }
    [[nodiscard]] Point2 xy(std::uint32_t v) const {
        return {m_arrays->mesh.vertices[v].x, m_arrays->mesh.vertices[v].y};
    }
    [[nodiscard]] const Point3& vertex(std::uint32_t v) const { return m_arrays->mesh.vertices[v]; }
    [[nodiscard]] std::uint32_t from(std::size_t h) const { return m_arrays->mesh.triangles[h]; }
    [[nodiscard]] std::uint32_t to(std::size_t h) const {
        return m_arrays->mesh.triangles[nextHalfEdge(h)];
    }
    /// The twin of `h`, or kNoHalfEdge on the convex hull. O(1).
    [[nodiscard]] std::size_t twin(std::size_t h) const;
    [[nodiscard]] bool isConstrained(std::size_t h) const { return m_arrays->constrained[h] != 0; }
    /// Sets the flag of `h` and of its twin.
    void setConstrained(std::size_t h, bool constrained);
    /// A half-edge leaving `v`. O(1), except that the first vertex asked for whose triangle
    /// is not known yet (neither written since nor found by locate or rememberTriangleOf)
    /// completes the vertex-to-triangle map, O(n) once.
    [[nodiscard]] std::size_t halfEdgeLeaving(std::uint32_t v) const;
    /// Notes the triangle of `h` as one holding both its vertices (those in the zone, for a
    /// view).
    void rememberTriangleOf(std::size_t h);
    /// Notes triangle t as one holding vertex v, a corner of it; nothing for a view when v lies
    /// outside its zone.
    void rememberTriangle(std::uint32_t v, std::size_t t);

    /// Every half-edge leaving `v`, counter-clockwise, then (when `v` is on the hull) the
    /// hull half-edge arriving at `v`; `visit(h)` returns true to stop. O(degree).
    template <class Visit> void forEachHalfEdgeAround(std::uint32_t v, Visit&& visit) const;

    /// Locates `p`, walking from triangle `startTriangle` (a remembering stochastic walk,
    /// which terminates on any triangulation, constrained ones included). A view starts from a
    /// triangle with a corner in its zone and refuses to cross an edge with neither end in it.
    [[nodiscard]] MeshLocation locate(const Point2& p, std::size_t startTriangle);

    /// Inserts `p` at `where` (InTriangle or OnEdge, as locate found it) as a new vertex with
    /// source index `source`, then restores the constrained Delaunay property by Lawson flips
    /// that never flip a constrained edge. A constrained edge split by `p` stays constrained
    /// in both halves; `onSplit(a, b, p)` is told. Returns the new vertex. A view refuses when
    /// it does not own the triangles split or has no slots left; a flip across its zone's edge
    /// is left to takePending.
    template <class OnSplit>
    std::uint32_t insertPoint(const Point3& p, std::uint32_t source, const MeshLocation& where,
                              OnSplit&& onSplit);

    /// The half-edge a -> b, or b -> a on the hull, or kNoHalfEdge when a-b is no edge.
    /// O(degree of a).
    [[nodiscard]] std::size_t findEdge(std::uint32_t a, std::uint32_t b) const;
    /// Flips the edge of `h` (interior, unconstrained, its quadrilateral strictly convex).
    /// Afterwards triangle h/3 is (a, d, c) and the twin's triangle (d, b, c), where h ran
    /// a -> b in triangle (a, b, c) and d was opposite across it.
    void flip(std::size_t h);

    /// An edge as its two vertices (either order), with a half-edge that held it when it was
    /// recorded: flips renumber half-edges, so the hint is checked before it is used.
    struct Edge {
        std::uint32_t a;
        std::uint32_t b;
        std::size_t hint = kNoHalfEdge;
    };
    /// The half-edge of `edge` now (its hint when still valid, else findEdge), or kNoHalfEdge.
    [[nodiscard]] std::size_t find(const Edge& edge) const;
    /// flip(h), adding the five half-edges of the two new triangles to `touched` (the new
    /// diagonal first, as the half-edge of triangle h/3).
    void flipAndRecord(std::size_t h, std::vector<std::size_t>& touched);
    /// flipAndRecord(h) where g is twin(h).
    void flipAndRecord(std::size_t h, std::size_t g, std::vector<std::size_t>& touched);
    /// Lawson's flips from the half-edges in `stack`, spreading to the neighbours of every
    /// flip, never across a constrained edge: afterwards the edges at those places, and every
    /// edge a flip made or moved, are locally constrained Delaunay. A flip only rewrites its two
    /// triangles and records all five of their edges, so an edge recorded earlier is either
    /// still where it was recorded or recorded again: half-edge places need no check that they
    /// still hold the edge meant (a place now holding another edge is checked, harmlessly).
    /// Empties `stack`. A view leaves a flip of a triangle it does not own to takePending.
    void restoreDelaunay(std::vector<std::size_t>& stack);
    /// The edges a view left not locally Delaunay (flips across its zone's edge), and empties
    /// the list.
    [[nodiscard]] std::vector<Edge> takePending() { return std::move(m_pending); }
    /// Makes the flips `view` left undone (takePending), once no view works: those of its edges
    /// that are still edges and not locally Delaunay, and what they lead to.
    void makePendingFlips(CdtMesh& view);

    /// A triangle of a cavity's new triangulation: its corners, counter-clockwise, and for
    /// each edge (corner i to corner (i + 1) % 3) what lies across it: the position of another
    /// new triangle in the list, or kCavityBoundary | k for the k-th boundary half-edge.
    struct CavityTriangle {
        static constexpr std::uint32_t kCavityBoundary = 0x80000000U;
        std::array<std::uint32_t, 3> corners;
        std::array<std::uint32_t, 3> across;
    };
    /// Replaces the triangles `slots` (a region of the mesh) by `triangles`, the k-th written
    /// into slots[k]. `boundary` lists the half-edges of the region's triangles on its boundary;
    /// a new triangle's edge on the k-th keeps that half-edge's direction, its neighbour outside
    /// and its flag; an edge between two new triangles is unconstrained. std::logic_error when
    /// the counts differ or a new edge on the boundary has other vertices than its half-edge
    /// (checked before the region's triangles are written). O(triangles).
    void replaceCavity(std::span<const std::size_t> slots, std::span<const std::size_t> boundary,
                       std::span<const CavityTriangle> triangles);

private:
    /// The corner of `triangle` that is `v` (0, 1 or 2); std::logic_error when none is.
    [[nodiscard]] std::size_t cornerOf(std::int32_t triangle, std::uint32_t v) const;
    [[noreturn, gnu::cold]] static void throwUnlinked();
    /// Points the half-edge of triangle `outer` that starts at `edgeStart` at `triangle`, its
    /// new neighbour across that edge; nothing when `outer` is kNoNeighbour (the hull).
    void relink(std::int32_t outer, std::uint32_t edgeStart, std::size_t triangle);
    /// flip(h) where g is twin(h).
    void flipAcross(std::size_t h, std::size_t g);
    /// Writes the corners of triangle `t` as (a, b, c) and points the three vertices at it;
    /// neighbours and flags are the caller's to write.
    void writeCorners(std::size_t t, std::uint32_t a, std::uint32_t b, std::uint32_t c);
    /// Writes triangle `t` as (a, b, c) with no neighbours and no flags, and points the three
    /// vertices at it.
    void writeTriangle(std::size_t t, std::uint32_t a, std::uint32_t b, std::uint32_t c);
    /// Makes `h` and `other` twins (`other` may be kNoHalfEdge: `h` is then a hull edge).
    void link(std::size_t h, std::size_t other);
    /// Sets the flag of `h` alone (the twin is set by the caller).
    void setFlag(std::size_t h, bool constrained) {
        m_arrays->constrained[h] = constrained ? 1 : 0;
    }
    std::size_t addTriangle();
    std::uint32_t addVertex(const Point3& p, std::uint32_t source);
    void splitTriangle(std::size_t h, std::uint32_t v, std::vector<std::size_t>& toCheck);
    void splitEdge(std::size_t h, std::uint32_t v, std::vector<std::size_t>& toCheck);
    void legalise(std::uint32_t v, std::vector<std::size_t>& toCheck);

    /// The arrays: the mesh's own, or for a view the shared mesh's. The flags and the map are
    /// on huge pages like the mesh's (MeshArray): set up at every vertex and half-edge, and
    /// then read along the constraints at random places.
    struct Arrays {
        TinMesh mesh;
        MeshArray<std::uint8_t> constrained;
        /// A triangle holding each vertex, kUnknownTriangle until one is written or found:
        /// the constraints touch few of the vertices, so the map is completed
        /// (completeVertexMap) only when an unknown one is asked for, as index segments and
        /// polylines without triangles do.
        MeshArray<std::uint32_t> vertexTriangle;
    };
    static constexpr std::uint32_t kUnknownTriangle = 0xffffffffU;
    /// Asks for the triangles across triangle t's edges, and their corners, to be brought into
    /// cache (a view: those it may read).
    void prefetchAround(std::size_t t) const;
    /// Every vertex's triangle unknown, with as much room as the mesh has.
    void startVertexMap();
    void completeVertexMap() const;
    std::unique_ptr<Arrays> m_own;
    Arrays* m_arrays = nullptr;
    /// A view's zone, slots, and the flips it left.
    bool m_zoned = false;
    Zone m_zone;
    SlotRange m_vertexSlots;
    SlotRange m_triangleSlots;
    std::vector<Edge> m_pending;
    std::uint64_t m_walkRandom = 0x9e3779b97f4a7c15ULL;
    std::vector<std::uint8_t>* m_written = nullptr;
    /// insertPoint's stack of edges to legalise, kept to spare an allocation per point.
    std::vector<std::size_t> m_toCheck;
    /// replaceCavity's boundary half-edges as they were, kept to spare an allocation per cavity.
    struct BoundaryEdge {
        std::uint32_t from;
        std::uint32_t to;
        std::int32_t outer;
        std::uint8_t flag;
    };
    std::vector<BoundaryEdge> m_cavityBoundary;
};

// twin and cornerOf are in the header: every step of a walk, a flip or a cavity asks for a
// twin, from the other files of the constraint code too.
inline std::size_t CdtMesh::twin(std::size_t h) const {
    const std::int32_t neighbour = m_arrays->mesh.neighbours[h];
    if (neighbour < 0)
        return kNoHalfEdge;
    return 3 * static_cast<std::size_t>(neighbour) + cornerOf(neighbour, to(h));
}

// Selects rather than branches: which corner it is is a coin toss for the branch predictor.
inline std::size_t CdtMesh::cornerOf(std::int32_t triangle, std::uint32_t v) const {
    const std::uint32_t* corners =
        &m_arrays->mesh.triangles[3 * static_cast<std::size_t>(triangle)];
    const std::size_t corner = corners[1] == v ? 1 : (corners[2] == v ? 2 : 0);
    if (corners[corner] != v)
        throwUnlinked();
    return corner;
}

template <class Visit> void CdtMesh::forEachHalfEdgeAround(std::uint32_t v, Visit&& visit) const {
    const std::size_t start = halfEdgeLeaving(v);
    std::size_t h = start;
    for (;;) {
        if (visit(h))
            return;
        const std::size_t incoming = previousHalfEdge(h);
        const std::size_t next = twin(incoming);
        if (next == kNoHalfEdge) {
            // On the hull: the hull half-edge arriving at v, then the other way round.
            if (visit(incoming))
                return;
            break;
        }
        if (next == start)
            return;
        h = next;
    }
    h = start;
    for (;;) {
        const std::size_t back = twin(h);
        if (back == kNoHalfEdge)
            return;
        h = nextHalfEdge(back);
        if (visit(h))
            return;
    }
}

template <class OnSplit>
std::uint32_t CdtMesh::insertPoint(const Point3& p, std::uint32_t source, const MeshLocation& where,
                                   OnSplit&& onSplit) {
    if (m_zoned)
        requireInsertable(where);
    const std::uint32_t v = addVertex(p, source);
    std::vector<std::size_t>& toCheck = m_toCheck; // empty between insertions
    if (where.kind == MeshLocation::Kind::OnEdge) {
        const std::uint32_t a = from(where.halfEdge);
        const std::uint32_t b = to(where.halfEdge);
        const bool wasConstrained = isConstrained(where.halfEdge);
        splitEdge(where.halfEdge, v, toCheck);
        if (wasConstrained)
            onSplit(a, b, v);
    } else {
        splitTriangle(where.halfEdge, v, toCheck);
    }
    legalise(v, toCheck);
    return v;
}

} // namespace terratin::detail

#include "refine_mesh.hpp"

#include "terratin/geometry/predicates.hpp"
#include "terratin/huge_pages.hpp"
#include "terratin/triangulate/tin_mesh.hpp"

#include <cstdlib>
#include <stdexcept>

namespace terratin::detail {

namespace {

/// Slots a thread takes at a time: threads then never write neighbouring slots.
constexpr TriId kBlockSlots = 256;

constexpr int next(int i) { return i == 2 ? 0 : i + 1; }
constexpr int previous(int i) { return i == 0 ? 2 : i - 1; }

} // namespace

RefineMesh::RefineMesh(std::span<const Point2> points, std::size_t maxTriangles,
                       unsigned threads)
    : m_points(points),
      m_capacity(maxTriangles + (static_cast<std::size_t>(threads) + 2) * kBlockSlots) {
    if (m_capacity >= kNoTriangle)
        throw std::length_error("Refiner: more than 2^32 - 1 triangles");
    // Pages are touched only as blocks are taken, so memory follows the triangles in use.
    m_triangles = HugePageBuffer<MeshTriangle>(m_capacity);
}

TriId RefineMesh::allocate(Scratch& scratch) {
    if (scratch.next == scratch.end) {
        const TriId start = m_nextSlot.fetch_add(kBlockSlots, std::memory_order_relaxed);
        if (static_cast<std::size_t>(start) + kBlockSlots > m_capacity)
            throw std::length_error("Refiner: triangle slots exhausted");
        for (TriId t = start; t < start + kBlockSlots; ++t)
            m_triangles[t] = {{kNoVertex, kNoVertex, kNoVertex},
                              {kNoTriangle, kNoTriangle, kNoTriangle}, 0, 0};
        scratch.next = start;
        scratch.end = start + kBlockSlots;
    }
    return scratch.next++;
}

void RefineMesh::set(TriId t, std::array<VertexId, 3> v, std::array<TriId, 3> n) {
    MeshTriangle& triangle = m_triangles[t];
    triangle.v = v;
    triangle.n = n;
    const std::atomic_ref<std::uint32_t> version(triangle.version);
    version.store(version.load(std::memory_order_relaxed) + 1, std::memory_order_release);
}

void RefineMesh::relink(TriId in, TriId from, TriId to) {
    if (in == kNoTriangle)
        return;
    for (TriId& link : m_triangles[in].n)
        if (link == from) {
            link = to;
            return;
        }
}

void RefineMesh::startFromHull(std::span<const VertexId> hull) {
    // A fan from hull[0], then Lawson's flips over every edge until all are Delaunay.
    Scratch scratch;
    const std::size_t fanSize = hull.size() - 2;
    std::vector<TriId> fan(fanSize);
    for (TriId& t : fan)
        t = allocate(scratch);
    for (std::size_t i = 0; i < fanSize; ++i) {
        // (h0, h[i+1], h[i+2]): opposite h0 the hull edge, opposite h[i+1] the next
        // triangle, opposite h[i+2] the previous one.
        set(fan[i], {hull[0], hull[i + 1], hull[i + 2]},
            {kNoTriangle, i + 1 < fanSize ? fan[i + 1] : kNoTriangle,
             i > 0 ? fan[i - 1] : kNoTriangle});
    }
    // Unlike an insertion's, any edge of a flipped pair may now be illegal: all four outer
    // edges go back on the stack.
    std::vector<std::pair<TriId, int>> edges;
    for (std::size_t i = 0; i + 1 < fanSize; ++i)
        edges.emplace_back(fan[i], 1);
    while (!edges.empty()) {
        const auto [t, e] = edges.back();
        edges.pop_back();
        const TriId u = flipIfIllegal(t, e);
        if (u != kNoTriangle)
            for (const auto& edge :
                 {std::pair{t, 0}, std::pair{t, 2}, std::pair{u, 0}, std::pair{u, 1}})
                edges.push_back(edge);
    }
}

TriId RefineMesh::flipIfIllegal(TriId t, int e) {
    const MeshTriangle& triangle = m_triangles[t];
    const TriId u = triangle.n[static_cast<std::size_t>(e)];
    if (u == kNoTriangle)
        return kNoTriangle;
    const MeshTriangle& beyond = m_triangles[u];
    int f = 0;
    while (beyond.n[static_cast<std::size_t>(f)] != t)
        ++f;
    // t = (p, x, y) from corner e, u = (d, y, x) from corner f.
    const VertexId p = triangle.v[static_cast<std::size_t>(e)];
    const VertexId x = triangle.v[static_cast<std::size_t>(next(e))];
    const VertexId y = triangle.v[static_cast<std::size_t>(previous(e))];
    const VertexId d = beyond.v[static_cast<std::size_t>(f)];
    if (predicates::incircle(point(p), point(x), point(y), point(d)) <= 0.0)
        return kNoTriangle;
    const TriId tx = triangle.n[static_cast<std::size_t>(next(e))];     // across (y, p)
    const TriId ty = triangle.n[static_cast<std::size_t>(previous(e))]; // across (p, x)
    const TriId uy = beyond.n[static_cast<std::size_t>(next(f))];       // across (x, d)
    const TriId ux = beyond.n[static_cast<std::size_t>(previous(f))];   // across (d, y)
    set(t, {p, x, d}, {uy, u, ty});
    set(u, {p, d, y}, {ux, tx, t});
    relink(uy, u, t);
    relink(tx, t, u);
    return u;
}

TriId RefineMesh::walk(VertexId p, TriId start) const {
    TriId t = start;
    const Point2& q = point(p);
    for (;;) {
        const MeshTriangle& triangle = m_triangles[t];
        int exit = -1;
        for (int i = 0; i < 3 && exit < 0; ++i)
            if (predicates::orient2d(point(triangle.v[static_cast<std::size_t>(next(i))]),
                                     point(triangle.v[static_cast<std::size_t>(previous(i))]),
                                     q) < 0.0)
                exit = i;
        if (exit < 0)
            return t;
        t = triangle.n[static_cast<std::size_t>(exit)];
        if (t == kNoTriangle)
            throw std::logic_error("Refiner: a point outside the hull");
    }
}

int RefineMesh::edgeContaining(TriId t, VertexId p) const {
    const MeshTriangle& triangle = m_triangles[t];
    for (int i = 0; i < 3; ++i)
        if (predicates::orient2d(point(triangle.v[static_cast<std::size_t>(next(i))]),
                                 point(triangle.v[static_cast<std::size_t>(previous(i))]),
                                 point(p)) == 0.0)
            return i;
    return -1;
}

int RefineMesh::insert(VertexId p, TriId t, Scratch& scratch, std::vector<TriId>& fan) {
    const MeshTriangle original = m_triangles[t];
    const int e = edgeContaining(t, p);
    int growth = 2;
    std::vector<std::pair<TriId, int>>& pending = scratch.pending;
    if (e < 0) {
        // Three triangles with p first: (p, v1, v2) in t's slot, (p, v2, v0), (p, v0, v1).
        const auto [v0, v1, v2] = original.v;
        const auto [n0, n1, n2] = original.n;
        const TriId t1 = allocate(scratch);
        const TriId t2 = allocate(scratch);
        set(t, {p, v1, v2}, {n0, t1, t2});
        set(t1, {p, v2, v0}, {n1, t2, t});
        set(t2, {p, v0, v1}, {n2, t, t1});
        relink(n1, t, t1);
        relink(n2, t, t2);
        pending.insert(pending.end(), {{t, 0}, {t1, 0}, {t2, 0}});
    } else {
        // p on the edge (b, c) opposite a; u beyond it, if any, is (d, c, b).
        const VertexId a = original.v[static_cast<std::size_t>(e)];
        const VertexId b = original.v[static_cast<std::size_t>(next(e))];
        const VertexId c = original.v[static_cast<std::size_t>(previous(e))];
        const TriId u = original.n[static_cast<std::size_t>(e)];
        const TriId nb = original.n[static_cast<std::size_t>(next(e))];     // across (c, a)
        const TriId nc = original.n[static_cast<std::size_t>(previous(e))]; // across (a, b)
        const TriId t1 = allocate(scratch);
        if (u == kNoTriangle) {
            growth = 1;
            set(t, {p, a, b}, {nc, kNoTriangle, t1});
            set(t1, {p, c, a}, {nb, t, kNoTriangle});
            relink(nb, t, t1);
            pending.insert(pending.end(), {{t, 0}, {t1, 0}});
        } else {
            const MeshTriangle beyond = m_triangles[u];
            int f = 0;
            while (beyond.n[static_cast<std::size_t>(f)] != t)
                ++f;
            const VertexId d = beyond.v[static_cast<std::size_t>(f)];
            const TriId mc = beyond.n[static_cast<std::size_t>(next(f))];     // across (b, d)
            const TriId mb = beyond.n[static_cast<std::size_t>(previous(f))]; // across (d, c)
            const TriId u1 = allocate(scratch);
            set(t, {p, a, b}, {nc, u1, t1});
            set(t1, {p, c, a}, {nb, t, u});
            set(u, {p, d, c}, {mb, t1, u1});
            set(u1, {p, b, d}, {mc, u, t});
            relink(nb, t, t1);
            relink(mc, u, u1);
            pending.insert(pending.end(), {{t, 0}, {t1, 0}, {u, 0}, {u1, 0}});
        }
    }
    legalize(scratch);

    // The triangles around p all have p first (every one was made by the split or a flip);
    // t's slot still holds p. Turn one way, and on the hull the other way as well.
    TriId s = t;
    do {
        fan.push_back(s);
        s = m_triangles[s].n[2];
    } while (s != t && s != kNoTriangle);
    if (s == kNoTriangle)
        for (s = m_triangles[t].n[1]; s != kNoTriangle; s = m_triangles[s].n[1])
            fan.push_back(s);
    return growth;
}

void RefineMesh::legalize(Scratch& scratch) {
    // Only the edges opposite the new point can become illegal; flipped triangles keep it
    // first, so their new edges opposite it are edge 0 of both.
    std::vector<std::pair<TriId, int>>& pending = scratch.pending;
    while (!pending.empty()) {
        const TriId t = pending.back().first;
        pending.pop_back();
        const TriId u = flipIfIllegal(t, 0);
        if (u != kNoTriangle) {
            pending.emplace_back(t, 0);
            pending.emplace_back(u, 0);
        }
    }
}

void RefineMesh::extract(std::vector<std::uint32_t>& triangles,
                         std::vector<std::int32_t>& neighbours) const {
    const TriId slots = slotCount();
    std::vector<std::int32_t> index(slots, -1);
    std::int32_t count = 0;
    for (TriId t = 0; t < slots; ++t)
        if (inUse(t))
            index[t] = count++;
    triangles.resize(3 * static_cast<std::size_t>(count));
    neighbours.resize(3 * static_cast<std::size_t>(count));
    for (TriId t = 0; t < slots; ++t) {
        if (index[t] < 0)
            continue;
        const auto out = 3 * static_cast<std::size_t>(index[t]);
        const MeshTriangle& triangle = m_triangles[t];
        // TinMesh: neighbours[3t+i] across the edge from corner i to corner i+1, which is
        // the edge opposite corner i+2 here.
        for (std::size_t i = 0; i < 3; ++i) {
            triangles[out + i] = triangle.v[i];
            const TriId across = triangle.n[(i + 2) % 3];
            neighbours[out + i] = across == kNoTriangle ? kNoNeighbour : index[across];
        }
    }
}

} // namespace terratin::detail

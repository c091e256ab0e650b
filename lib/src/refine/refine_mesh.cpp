#include "refine_mesh.hpp"

#include "../huge_pages.hpp"
#include "../parallel/parallel_for.hpp"

#include "terratin/geometry/predicates.hpp"
#include "terratin/triangulate/tin_mesh.hpp"

#include <algorithm>
#include <cstdlib>
#include <stdexcept>

namespace terratin::detail {

namespace {

constexpr int next(int i) {
    return i == 2 ? 0 : i + 1;
}
constexpr int previous(int i) {
    return i == 0 ? 2 : i - 1;
}

} // namespace

RefineMesh::RefineMesh(std::span<const RefineVertex> vertices, std::size_t capacity)
    : m_vertices(vertices), m_capacity(capacity) {
    if (m_capacity >= kNoTriangle)
        throw std::length_error("Refiner: more than 2^32 - 1 triangles");
    // Pages are touched only as slots are used, so memory follows the triangles in use.
    m_triangles = HugePageBuffer<MeshTriangle>(m_capacity);
}

unsigned RefineMesh::addRegion(std::size_t slots) {
    const TriId begin = m_regions.empty() ? 0 : m_regions.back().end;
    if (begin + slots > m_capacity)
        throw std::length_error("Refiner: triangle slots exhausted");
    Region region;
    region.begin = begin;
    region.next = begin;
    region.end = begin + static_cast<TriId>(slots);
    m_regions.push_back(region);
    return static_cast<unsigned>(m_regions.size() - 1);
}

TriId RefineMesh::allocate(unsigned region) {
    Region& from = m_regions[region];
    if (from.next == from.end)
        throw std::length_error("Refiner: a region of triangle slots is exhausted");
    const TriId t = from.next++;
    m_triangles[t] = {{kNoVertex, kNoVertex, kNoVertex},
                      {kNoTriangle, kNoTriangle, kNoTriangle},
                      0,
                      StripRange::all()};
    return t;
}

std::vector<TriId> RefineMesh::slotsInUse() const {
    std::size_t handedOut = 0;
    for (const Region& region : m_regions)
        handedOut += region.next - region.begin;
    std::vector<TriId> slots;
    slots.reserve(handedOut);
    for (const Region& region : m_regions)
        for (TriId t = region.begin; t < region.next; ++t)
            if (inUse(t))
                slots.push_back(t);
    return slots;
}

TriId RefineMesh::slotEnd() const {
    TriId end = 0;
    for (const Region& region : m_regions)
        if (region.next > region.begin)
            end = region.next;
    return end;
}

std::size_t RefineMesh::memoryBytes() const {
    std::size_t slots = 0;
    for (const Region& region : m_regions)
        slots += region.next - region.begin;
    return slots * sizeof(MeshTriangle);
}

void RefineMesh::set(TriId t, std::array<VertexId, 3> v, std::array<TriId, 3> n) {
    MeshTriangle& triangle = m_triangles[t];
    triangle.v = v;
    triangle.n = n;
    const std::uint8_t a = m_vertices[v[0]].strip;
    const std::uint8_t b = m_vertices[v[1]].strip;
    const std::uint8_t c = m_vertices[v[2]].strip;
    triangle.strips = {std::min({a, b, c}), std::max({a, b, c})};
    const std::atomic_ref<std::uint32_t> version(triangle.version);
    version.store(version.load(std::memory_order_relaxed) + 1, std::memory_order_release);
}

void RefineMesh::relinkAcross(TriId in, VertexId a, VertexId b, TriId to) {
    if (in == kNoTriangle)
        return;
    // The corner that is neither a nor b faces the edge. Only the corners are read: another
    // thread may be rewriting a different link of the same (shared) triangle.
    MeshTriangle& triangle = m_triangles[in];
    for (std::size_t i = 0; i < 3; ++i)
        if (triangle.v[i] != a && triangle.v[i] != b) {
            triangle.n[i] = to;
            return;
        }
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

void RefineMesh::startFromHull(std::span<const VertexId> hull, unsigned region) {
    // A fan from hull[0], then Lawson's flips over every edge until all are Delaunay.
    const std::size_t fanSize = hull.size() - 2;
    std::vector<TriId> fan(fanSize);
    for (TriId& t : fan)
        t = allocate(region);
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
    const int f = beyond.edgeTowards(t);
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

int RefineMesh::exitEdge(TriId t, const Point2& q) const {
    const MeshTriangle& triangle = m_triangles[t];
    for (int i = 0; i < 3; ++i)
        if (predicates::orient2d(point(triangle.v[static_cast<std::size_t>(next(i))]),
                                 point(triangle.v[static_cast<std::size_t>(previous(i))]), q) < 0.0)
            return i;
    return -1;
}

TriId RefineMesh::walk(const Point2& q, TriId start) const {
    TriId t = start;
    for (int exit = exitEdge(t, q); exit >= 0; exit = exitEdge(t, q)) {
        t = m_triangles[t].n[static_cast<std::size_t>(exit)];
        if (t == kNoTriangle)
            throw std::logic_error("Refiner: a point outside the hull");
    }
    return t;
}

void RefineMesh::refuse(TriId met, StripRange allowed, InsertScratch& scratch) const {
    const StripRange strips = m_triangles[met].strips;
    scratch.needed = {std::min(allowed.first, strips.first), std::max(allowed.last, strips.last)};
}

void RefineMesh::requestNeighbours(TriId t) const {
    for (const TriId n : m_triangles[t].n)
        if (n != kNoTriangle)
            __builtin_prefetch(&m_triangles[n]);
}

TriId RefineMesh::walkWithin(const Point2& q, TriId start, StripRange allowed,
                             InsertScratch& scratch) const {
    TriId t = start;
    if (!allowed.contains(m_triangles[t].strips)) {
        refuse(t, allowed, scratch);
        return kNoTriangle;
    }
    for (int exit = exitEdge(t, q); exit >= 0; exit = exitEdge(t, q)) {
        t = m_triangles[t].n[static_cast<std::size_t>(exit)];
        if (t == kNoTriangle)
            throw std::logic_error("Refiner: a point outside the hull");
        if (!allowed.contains(m_triangles[t].strips)) {
            refuse(t, allowed, scratch);
            return kNoTriangle;
        }
    }
    return t;
}

bool RefineMesh::findCavity(const Point2& q, TriId t, StripRange allowed,
                            InsertScratch& scratch) const {
    std::vector<TriId>& cavity = scratch.cavity;
    std::vector<InsertScratch::Edge>& boundary = scratch.boundary;
    // A cavity triangle's neighbours are read when the search reaches it: their records are
    // requested as soon as it joins.
    requestNeighbours(t);
    cavity.assign(1, t);
    boundary.clear();
    for (std::size_t i = 0; i < cavity.size(); ++i) {
        const MeshTriangle& triangle = m_triangles[cavity[i]];
        // Each neighbour's corner across the edge is a vertex read nowhere else yet: the
        // three are requested together rather than met one after the other.
        for (const TriId u : triangle.n)
            if (u != kNoTriangle)
                for (const VertexId v : m_triangles[u].v)
                    __builtin_prefetch(&m_vertices[v]);
        for (int e = 0; e < 3; ++e) {
            const VertexId a = triangle.v[static_cast<std::size_t>(next(e))];
            const VertexId b = triangle.v[static_cast<std::size_t>(previous(e))];
            const TriId u = triangle.n[static_cast<std::size_t>(e)];
            if (u == kNoTriangle) {
                // p on this hull edge splits it: no triangle over it.
                if (predicates::orient2d(point(a), point(b), q) != 0.0)
                    boundary.push_back({a, b, u});
                continue;
            }
            if (std::find(cavity.begin(), cavity.end(), u) != cavity.end())
                continue;
            const MeshTriangle& beyond = m_triangles[u];
            // A point inside the edge (a, b) is strictly inside u's circumcircle too.
            if (predicates::incircle(point(beyond.v[0]), point(beyond.v[1]), point(beyond.v[2]),
                                     q) > 0.0) {
                if (!allowed.contains(beyond.strips)) {
                    refuse(u, allowed, scratch);
                    return false;
                }
                requestNeighbours(u);
                cavity.push_back(u);
            } else {
                boundary.push_back({a, b, u});
            }
        }
    }
    return true;
}

void RefineMesh::makeFan(VertexId p, unsigned region, InsertScratch& scratch) {
    const std::vector<TriId>& cavity = scratch.cavity;
    const std::vector<InsertScratch::Edge>& boundary = scratch.boundary;
    std::vector<TriId>& fan = scratch.fan;
    fan.resize(boundary.size());
    for (std::size_t k = 0; k < fan.size(); ++k)
        fan[k] = k < cavity.size() ? cavity[k] : allocate(region);
    // The fan triangle of the boundary edge that starts (or ends) at v; none beside the split
    // hull edge.
    const auto fanFrom = [&](VertexId v, bool atStart) {
        for (std::size_t k = 0; k < boundary.size(); ++k)
            if ((atStart ? boundary[k].a : boundary[k].b) == v)
                return fan[k];
        return kNoTriangle;
    };
    for (std::size_t k = 0; k < fan.size(); ++k) {
        const auto [a, b, beyond] = boundary[k];
        // (p, a, b): across (a, b) the triangle beyond, across (b, p) the fan triangle of the
        // edge leaving b, across (p, a) the one of the edge arriving at a.
        set(fan[k], {p, a, b}, {beyond, fanFrom(b, true), fanFrom(a, false)});
        relinkAcross(beyond, a, b, fan[k]);
    }
}

int RefineMesh::tryInsert(VertexId p, TriId start, StripRange allowed, unsigned region,
                          InsertScratch& scratch, int maxAdded) {
    const Point2& q = point(p);
    // The walk, then the cavity by a search over neighbours; nothing is written until both
    // are known to stay within the allowed strips.
    const TriId t = walkWithin(q, start, allowed, scratch);
    if (t == kNoTriangle || !findCavity(q, t, allowed, scratch))
        return 0;
    const int added =
        static_cast<int>(scratch.boundary.size()) - static_cast<int>(scratch.cavity.size());
    if (added > maxAdded)
        return 0;
    makeFan(p, region, scratch);
    return added;
}

void RefineMesh::extract(MeshArray<std::uint32_t>& triangles, MeshArray<std::int32_t>& neighbours,
                         unsigned threads) const {
    const std::vector<TriId> slots = slotsInUse();
    std::vector<std::int32_t> index(slotEnd(), -1);
    for (std::size_t k = 0; k < slots.size(); ++k)
        index[slots[k]] = static_cast<std::int32_t>(k);
    triangles.resize(3 * slots.size());
    neighbours.resize(3 * slots.size());
    parallelFor(slots.size(), threads, [&](unsigned, std::size_t begin, std::size_t end) {
        for (std::size_t k = begin; k < end; ++k) {
            const MeshTriangle& triangle = m_triangles[slots[k]];
            // TinMesh: neighbours[3t+i] across the edge from corner i to corner i+1, which is
            // the edge opposite corner i+2 here.
            for (std::size_t i = 0; i < 3; ++i) {
                triangles[3 * k + i] = triangle.v[i];
                const TriId across = triangle.n[(i + 2) % 3];
                neighbours[3 * k + i] = across == kNoTriangle ? kNoNeighbour : index[across];
            }
        }
    });
}

} // namespace terratin::detail

#include "cavity_mesh.hpp"

#include "../parallel/parallel_for.hpp"

#include "terratin/error.hpp"
#include "terratin/geometry/predicates.hpp"

#include <algorithm>
#include <memory>
#include <stdexcept>

namespace terratin::detail {

namespace {

constexpr CavityLink link(CavityTriangleId triangle, unsigned corner) {
    return triangle * 4U + corner;
}
constexpr CavityTriangleId linkedTriangle(CavityLink l) {
    return l >> 2U;
}
constexpr unsigned linkedCorner(CavityLink l) {
    return l & 3U;
}
constexpr unsigned next(unsigned corner) {
    return corner == 2 ? 0 : corner + 1;
}
constexpr unsigned previous(unsigned corner) {
    return corner == 0 ? 2 : corner - 1;
}

bool isGhost(const CavityTriangle& t) {
    return t.corners[2] == kGhostVertex;
}

// p strictly between a and b, all three on one line.
bool strictlyBetween(const Point2& a, const Point2& b, const Point2& p) {
    if (a.x != b.x)
        return (a.x < p.x && p.x < b.x) || (b.x < p.x && p.x < a.x);
    return (a.y < p.y && p.y < b.y) || (b.y < p.y && p.y < a.y);
}

} // namespace

CavityMesh::CavityMesh(std::span<const Point2> points, std::span<const std::uint8_t> vertexStrip,
                       std::size_t capacity)
    : m_points(points), m_vertexStrip(vertexStrip) {
    // A link holds a slot times four.
    if (capacity >= std::size_t{kNoCavityTriangle} / 4)
        throw InvalidInputError("Triangulator: too many points");
    m_triangles = HugePageBuffer<CavityTriangle>(capacity);
    m_owner = HugePageBuffer<std::uint8_t>(capacity);
}

CavityMesh::Scratch CavityMesh::makeScratch(std::size_t slots) {
    if (slots > m_triangles.size() - m_reserved)
        throw std::logic_error("CavityMesh: regions exceed the capacity");
    Scratch scratch;
    scratch.regionBegin = static_cast<CavityTriangleId>(m_reserved);
    scratch.nextSlot = scratch.regionBegin;
    m_reserved += slots;
    scratch.regionEnd = static_cast<CavityTriangleId>(m_reserved);
    m_regions.emplace_back(scratch.regionBegin, scratch.regionBegin);
    return scratch;
}

std::uint8_t CavityMesh::ownerFromCorners(const std::array<CavityVertex, 3>& corners) const {
    return m_vertexStrip.empty() ? 0 : groupFromCorners(corners, 0);
}

std::uint8_t CavityMesh::groupFromCorners(const std::array<CavityVertex, 3>& corners,
                                          unsigned level) const {
    const auto group = static_cast<std::uint8_t>(m_vertexStrip[corners[0]] >> level);
    if ((m_vertexStrip[corners[1]] >> level) != group ||
        (corners[2] != kGhostVertex && (m_vertexStrip[corners[2]] >> level) != group))
        return kSharedOwner;
    return group;
}

CavityTriangleId CavityMesh::allocate(Scratch& scratch) {
    if (scratch.nextSlot == scratch.regionEnd)
        throw std::logic_error("CavityMesh: a scratch region is full");
    return scratch.nextSlot++;
}

void CavityMesh::closeScratch(const Scratch& scratch) {
    for (auto& [begin, used] : m_regions)
        if (begin == scratch.regionBegin)
            used = scratch.nextSlot;
}

CavityTriangleId CavityMesh::start(CavityVertex a, CavityVertex b, CavityVertex c,
                                   Scratch& scratch) {
    if (predicates::orient2d(m_points[a], m_points[b], m_points[c]) < 0)
        std::swap(b, c);
    // Slots s[0]-s[3]: the real triangle, then the ghosts of its edges bc, ca and ab. The
    // ghost of hull edge x -> y is (y, x, infinity): its corner 0 faces the previous hull
    // edge's ghost (across the edge x - infinity) and its corner 1 the next one's.
    std::array<CavityTriangleId, 4> s{};
    for (CavityTriangleId& slot : s)
        slot = allocate(scratch);
    const std::array<CavityTriangle, 4> start{{
        {{a, b, c}, {link(s[1], 2), link(s[2], 2), link(s[3], 2)}},
        {{c, b, kGhostVertex}, {link(s[3], 1), link(s[2], 0), link(s[0], 0)}},
        {{a, c, kGhostVertex}, {link(s[1], 1), link(s[3], 0), link(s[0], 1)}},
        {{b, a, kGhostVertex}, {link(s[2], 1), link(s[1], 0), link(s[0], 2)}},
    }};
    for (std::size_t i = 0; i < start.size(); ++i) {
        m_triangles[s[i]] = start[i];
        m_owner[s[i]] = ownerFromCorners(start[i].corners);
    }
    return s[0];
}

bool CavityMesh::inConflict(const CavityTriangle& t, const Point2& p) const {
    const Point2& a = m_points[t.corners[0]];
    const Point2& b = m_points[t.corners[1]];
    if (!isGhost(t))
        return predicates::incircleTieBroken(a, b, m_points[t.corners[2]], p) > 0;
    // The ghost of hull edge b -> a: p sees that edge from outside, or lies inside it.
    const double side = predicates::orient2d(a, b, p);
    return side > 0 || (side == 0 && strictlyBetween(a, b, p));
}

CavityTriangleId CavityMesh::locate(CavityVertex p, CavityTriangleId start, std::uint8_t owner,
                                    unsigned level) const {
    const Point2& q = m_points[p];
    const auto allowed = [&](CavityTriangleId t) { return mayTouch(t, owner, level); };
    CavityTriangleId t = start;
    if (!allowed(t))
        return kNoCavityTriangle;
    if (isGhost(m_triangles[t])) {
        if (inConflict(m_triangles[t], q))
            return t;
        t = linkedTriangle(m_triangles[t].links[2]);
        if (!allowed(t))
            return kNoCavityTriangle;
    }
    // Visibility walk (terminates on a Delaunay triangulation, Edelsbrunner 1989): cross an
    // edge that has q strictly on its far side; the edge just crossed need not be tested.
    unsigned entered = 3;
    for (;;) {
        const CavityTriangle& triangle = m_triangles[t];
        unsigned crossing = 3;
        for (unsigned k = 0; k < 3; ++k) {
            if (k == entered)
                continue;
            if (predicates::orient2d(m_points[triangle.corners[next(k)]],
                                     m_points[triangle.corners[previous(k)]], q) < 0) {
                crossing = k;
                break;
            }
        }
        if (crossing == 3)
            return t;
        const CavityLink across = triangle.links[crossing];
        t = linkedTriangle(across);
        if (!allowed(t))
            return kNoCavityTriangle;
        if (isGhost(m_triangles[t]))
            return t;
        entered = linkedCorner(across);
    }
}

bool CavityMesh::collectCavity(const Point2& p, CavityTriangleId first, std::uint8_t owner,
                               unsigned level, Scratch& scratch) const {
    // Depth first, each triangle's edges counter-clockwise from the one after the edge it was
    // entered by: the boundary comes out in counter-clockwise order around p. The cavity of a
    // Delaunay triangulation is a disk with every vertex on its boundary, so no triangle is
    // reached twice.
    scratch.cavity.assign(1, first);
    scratch.boundary.clear();
    scratch.stack.assign(1, {first, 0, 3});
    while (!scratch.stack.empty()) {
        Scratch::Frame& frame = scratch.stack.back();
        if (frame.edgesLeft == 0) {
            scratch.stack.pop_back();
            continue;
        }
        const CavityTriangleId t = frame.triangle;
        const unsigned edge = frame.nextEdge;
        frame.nextEdge = static_cast<std::uint8_t>(next(edge));
        --frame.edgesLeft;
        const CavityTriangle& triangle = m_triangles[t];
        const CavityLink across = triangle.links[edge];
        const CavityTriangleId neighbour = linkedTriangle(across);
        if (inConflict(m_triangles[neighbour], p)) {
            if (!mayTouch(neighbour, owner, level))
                return false;
            scratch.cavity.push_back(neighbour);
            const auto entry = static_cast<std::uint8_t>(next(linkedCorner(across)));
            scratch.stack.push_back({neighbour, entry, 2});
        } else {
            scratch.boundary.push_back(
                {triangle.corners[next(edge)], triangle.corners[previous(edge)], across});
        }
    }
    return true;
}

CavityTriangleId CavityMesh::fillCavity(CavityVertex p, std::uint8_t owner, unsigned level,
                                        Scratch& scratch) {
    // Boundary edge i, from -> to, becomes triangle (from, to, p), rotated so that a vertex at
    // infinity is corner 2; shiftOf(i) is the corner that corner 0 of (from, to, p) became.
    const std::size_t count = scratch.boundary.size();
    // A disk triangulated without inner vertices has two triangles fewer than edges.
    if (scratch.cavity.size() + 2 != count)
        throw std::logic_error("CavityMesh: cavity is not a disk");
    scratch.cavity.push_back(allocate(scratch));
    scratch.cavity.push_back(allocate(scratch));
    const std::vector<CavityTriangleId>& slots = scratch.cavity;
    const auto shiftOf = [&](std::size_t i) -> unsigned {
        const Scratch::BoundaryEdge& edge = scratch.boundary[i];
        return edge.from == kGhostVertex ? 2U : edge.to == kGhostVertex ? 1U : 0U;
    };
    for (std::size_t i = 0; i < count; ++i) {
        const Scratch::BoundaryEdge& edge = scratch.boundary[i];
        const std::size_t after = i + 1 == count ? 0 : i + 1;
        const std::size_t before = i == 0 ? count - 1 : i - 1;
        const unsigned shift = shiftOf(i);
        const unsigned shiftAfter = shiftOf(after);
        const unsigned shiftBefore = shiftOf(before);
        // Unrotated: links[0] crosses (to, p), corner 1 of the next triangle; links[1]
        // crosses (p, from), corner 0 of the previous one; links[2] is the outside.
        const std::array<CavityVertex, 3> corners{edge.from, edge.to, p};
        const std::array<CavityLink, 3> links{link(slots[after], (1 + shiftAfter) % 3),
                                              link(slots[before], shiftBefore), edge.outside};
        CavityTriangle& triangle = m_triangles[slots[i]];
        for (unsigned k = 0; k < 3; ++k) {
            triangle.corners[(k + shift) % 3] = corners[k];
            triangle.links[(k + shift) % 3] = links[k];
        }
        m_triangles[linkedTriangle(edge.outside)].links[linkedCorner(edge.outside)] =
            link(slots[i], (2 + shift) % 3);
        // Within a strip the label is the strip; a merged group's triangles keep strip labels.
        m_owner[slots[i]] =
            owner == kAnyOwner || level != 0 ? ownerFromCorners(triangle.corners) : owner;
    }
    return slots[0];
}

bool CavityMesh::insert(CavityVertex p, CavityTriangleId& hint, Scratch& scratch,
                        std::uint8_t owner, unsigned level) {
    const CavityTriangleId first = locate(p, hint, owner, level);
    if (first == kNoCavityTriangle)
        return false;
    if (!collectCavity(m_points[p], first, owner, level, scratch))
        return false;
    hint = fillCavity(p, owner, level, scratch);
    return true;
}

void CavityMesh::extract(MeshArray<std::uint32_t>& triangles, MeshArray<std::int32_t>& neighbours,
                         unsigned threads) const {
    // The used slots of every region, one region after the other, as positions [0, total).
    std::vector<std::size_t> regionOffset{0};
    for (const auto& [begin, used] : m_regions)
        regionOffset.push_back(regionOffset.back() + (used - begin));
    const std::size_t total = regionOffset.back();
    // Calls visit(slot) for the slots at positions [begin, end), region by region.
    const auto forEachSlot = [&](std::size_t begin, std::size_t end, auto&& visit) {
        for (std::size_t region = 0; region < m_regions.size(); ++region) {
            const std::size_t from = std::max(begin, regionOffset[region]);
            const std::size_t to = std::min(end, regionOffset[region + 1]);
            for (std::size_t position = from; position < to; ++position)
                visit(static_cast<CavityTriangleId>(m_regions[region].first +
                                                    (position - regionOffset[region])));
        }
    };
    // number[slot]: the triangle's index in the output, kGhostNumber for a ghost. Real
    // triangles are numbered in position order: counted per block, then numbered. Only the
    // used slots are written (and so only their pages touched).
    constexpr std::uint32_t kGhostNumber = 0xFFFFFFFFU;
    const HugePageBuffer<std::uint32_t> number(m_reserved);
    const unsigned blocks = parallelForThreads(total, threads);
    std::vector<std::uint32_t> blockFirst(blocks + 1, 0);
    parallelFor(total, threads, [&](unsigned block, std::size_t begin, std::size_t end) {
        std::uint32_t real = 0;
        forEachSlot(begin, end,
                    [&](CavityTriangleId t) { real += isGhost(m_triangles[t]) ? 0 : 1; });
        blockFirst[block + 1] = real;
    });
    for (unsigned block = 0; block < blocks; ++block)
        blockFirst[block + 1] += blockFirst[block];
    parallelFor(total, threads, [&](unsigned block, std::size_t begin, std::size_t end) {
        std::uint32_t id = blockFirst[block];
        forEachSlot(begin, end, [&](CavityTriangleId t) {
            number[t] = isGhost(m_triangles[t]) ? kGhostNumber : id++;
        });
    });
    const std::size_t realCount = blockFirst[blocks];
    triangles.resize(3 * realCount);
    neighbours.resize(3 * realCount);
    parallelFor(total, threads, [&](unsigned, std::size_t begin, std::size_t end) {
        forEachSlot(begin, end, [&](CavityTriangleId t) {
            if (number[t] == kGhostNumber)
                return;
            const CavityTriangle& triangle = m_triangles[t];
            const std::size_t base = 3 * std::size_t{number[t]};
            for (unsigned i = 0; i < 3; ++i) {
                triangles[base + i] = triangle.corners[i];
                // TinMesh's edge i runs from corner i to corner i + 1: opposite corner i + 2.
                const std::uint32_t across = number[linkedTriangle(triangle.links[previous(i)])];
                neighbours[base + i] =
                    across == kGhostNumber ? kNoNeighbour : static_cast<std::int32_t>(across);
            }
        });
    });
}

std::size_t CavityMesh::memoryBytes() const {
    std::size_t slots = 0;
    for (const auto& [begin, used] : m_regions)
        slots += used - begin;
    return slots * (sizeof(CavityTriangle) + sizeof(std::uint8_t));
}

} // namespace terratin::detail

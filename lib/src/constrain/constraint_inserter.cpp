#include "constraint_inserter.hpp"

#include "terratin/geometry/predicates.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace terratin::detail {

namespace {

// How close, in units of 2^-52 times the largest coordinate involved (4 to 8 ulps), a vertex
// must be to a segment or a crossing to be taken as on it. The crossing vertices computed
// below lie within about an ulp of both segments (the rounding of t, of the product and of the
// sum); twice that each way, and a margin, is 4.
constexpr double kSnapUlps = 4.0;

} // namespace

std::optional<std::uint32_t> ConstraintInserter::insertPoint(const Point3& p, bool jump) {
    if (jump) {
        if (!m_buckets)
            m_buckets.emplace(m_mesh.mesh().vertices);
        m_hintTriangle = m_mesh.halfEdgeLeaving(m_buckets->vertexNear({p.x, p.y})) / 3;
    }
    return insertPointFrom(p, m_hintTriangle);
}

std::optional<std::uint32_t> ConstraintInserter::insertPointFrom(const Point3& p,
                                                                 std::size_t triangle) {
    m_poll.step();
    const MeshLocation where = m_mesh.locate({p.x, p.y}, triangle);
    if (where.kind == MeshLocation::Kind::OutsideHull)
        return std::nullopt;
    m_hintTriangle = where.halfEdge / 3;
    if (where.kind == MeshLocation::Kind::OnVertex)
        return where.vertex;
    const std::uint32_t v = insertVertex(p, kConstraintPointSource, where);
    ++m_addedPoints; // after: a zone may refuse the insertion
    return v;
}

void ConstraintInserter::requireEdgeInZone(std::uint32_t a, std::uint32_t b) const {
    if (m_sharedOwners != nullptr && (!m_mesh.inZone(a) || !m_mesh.inZone(b)))
        throw ZoneRefusal{};
}

ConstraintOwners::Owners ConstraintInserter::takeOwners(std::uint32_t a, std::uint32_t b) {
    ConstraintOwners::Owners owners = m_owners.take(a, b);
    if (m_sharedOwners == nullptr || !m_sharedOwners->contains(a, b))
        return owners;
    if (!m_takenShared.insert(ConstraintOwners::edgeKey(a, b)).second)
        return owners; // taken before: what it has now is this zone's
    for (const std::uint32_t owner : m_sharedOwners->ownersOf(a, b))
        if (std::find(owners.begin(), owners.end(), owner) == owners.end())
            owners.push_back(owner);
    return owners;
}

void ConstraintInserter::startChain(std::uint32_t owner, std::uint32_t a, std::uint32_t b) {
    if (m_deferChains)
        m_chainEdits.start(owner, a, b);
    else
        m_chains->start(owner, a, b);
}

void ConstraintInserter::splitChains(const ConstraintOwners::Owners& owners, std::uint32_t x,
                                     std::uint32_t y, std::uint32_t w) {
    if (m_deferChains)
        m_chainEdits.insertBetween(owners, x, y, w);
    else
        m_chains->insertBetween(owners, x, y, w);
}

std::uint32_t ConstraintInserter::insertVertex(const Point3& p, std::uint32_t source,
                                               const MeshLocation& where) {
    if (where.kind == MeshLocation::Kind::OnEdge && m_mesh.isConstrained(where.halfEdge))
        requireEdgeInZone(m_mesh.from(where.halfEdge), m_mesh.to(where.halfEdge));
    const std::uint32_t v = m_mesh.insertPoint(
        p, source, where, [this](std::uint32_t a, std::uint32_t b, std::uint32_t middle) {
            const ConstraintOwners::Owners owners = takeOwners(a, b);
            m_owners.add(a, middle, owners);
            m_owners.add(middle, b, owners);
            splitChains(owners, a, b, middle);
        });
    m_hintTriangle = m_mesh.halfEdgeLeaving(v) / 3;
    return v;
}

void ConstraintInserter::insertSegment(std::uint32_t a, std::uint32_t b, std::uint32_t owner) {
    startChain(owner, a, b);
    m_pieces.push_back({a, b, {owner}});
    insertPendingPieces(owner);
    ++m_segmentsInserted;
}

void ConstraintInserter::insertPieces(std::vector<Piece> pieces) {
    if (pieces.empty())
        return;
    const std::uint32_t owner = pieces.front().owners.front();
    m_pieces = std::move(pieces);
    insertPendingPieces(owner);
    ++m_segmentsInserted;
}

void ConstraintInserter::insertPendingPieces(std::uint32_t owner) {
    m_crossingsMet.clear();
    // Each crossing makes at most four pieces and there are fewer than 3n constrained edges to
    // cross, so more pieces than this means a loop: an error rather than a hang.
    const std::size_t maxPieces = 64 + 16 * m_mesh.vertexCount();
    for (std::size_t pieces = 0; !m_pieces.empty(); ++pieces) {
        if (pieces > maxPieces)
            throw std::logic_error("insertConstraints: segment " + std::to_string(owner) +
                                   " does not converge");
        m_poll.step(); // a segment that many others cross goes in as many pieces
        Piece piece = std::move(m_pieces.back());
        m_pieces.pop_back();
        try {
            insertPiece(piece);
        } catch (const ZoneRefusal&) {
            m_pieces.push_back(std::move(piece)); // what is left of it, for takePieces
            throw;
        }
    }
}

void ConstraintInserter::insertPiece(Piece& piece) {
    const std::uint32_t v = piece.to;
    while (piece.from != v) {
        const std::uint32_t u = piece.from;
        const SegmentStart start = findSegmentStart(m_mesh, u, v);
        if (start.kind == SegmentStart::Kind::AlongEdge) {
            m_mesh.rememberTriangleOf(start.halfEdge); // the next piece starts at its vertex
            markConstrained(start.halfEdge, piece.owners);
            splitChains(piece.owners, u, v, start.vertex);
            piece.from = start.vertex;
            continue;
        }
        const std::size_t blocking = walkCrossedEdges(m_mesh, u, v, start, m_crossed);
        if (blocking != kNoHalfEdge) {
            splitAtCrossing(u, v, piece.owners, blocking);
            piece.from = v; // the pieces it pushed go on
            return;
        }
        std::size_t segment = retriangulateCavity(m_mesh, u, m_crossed, m_cavity);
        if (segment == kNoHalfEdge)
            segment = flipSegmentIn(m_mesh, u, m_crossed);
        markConstrained(segment, piece.owners);
        splitChains(piece.owners, u, v, m_crossed.end);
        piece.from = m_crossed.end;
    }
}

void ConstraintInserter::markConstrained(std::size_t h, const ConstraintOwners::Owners& owners) {
    m_mesh.setConstrained(h, true);
    m_owners.add(m_mesh.from(h), m_mesh.to(h), owners);
}

// u -> v crosses the constrained edge c -> d: both segments are bent through a vertex at the
// crossing, computed along c -> d (the segment inserted first). Rounding may put that vertex an
// ulp off either segment, so it is found again by location, c -> d is unmarked and both are
// re-inserted in two pieces. When c or d lies within rounding distance of u -> v, u -> v goes
// through it instead: a later segment through an earlier crossing then uses its vertex rather
// than making another one a rounding away from it.
//
// Where crossings crowd within a few ulps of each other, the rounding of these rules can send
// the pieces round in a circle (c -> d re-inserted through a vertex that routes it back onto
// c -> d). A crossing met a second time while inserting one segment is therefore resolved the
// way that cannot recur: u -> v goes through whichever of c and d is nearer the crossing, and
// c -> d stays as it is. That only happens inside such a crowd, so the detour is a few ulps.
void ConstraintInserter::splitAtCrossing(std::uint32_t u, std::uint32_t v,
                                         const ConstraintOwners::Owners& owners,
                                         std::size_t crossed) {
    const std::uint32_t c = m_mesh.from(crossed);
    const std::uint32_t d = m_mesh.to(crossed);
    const Point2 pu = m_mesh.xy(u);
    const Point2 pv = m_mesh.xy(v);
    // Distances of c and d from the line uv, times |uv|; their signs differ exactly.
    const double sideC = predicates::orient2d(pu, pv, m_mesh.xy(c));
    const double sideD = predicates::orient2d(pu, pv, m_mesh.xy(d));
    const double t = std::clamp(sideC / (sideC - sideD), 0.0, 1.0);
    const bool metBefore = !m_crossingsMet.insert({u, v, c, d}).second;
    std::optional<std::uint32_t> near = nearEndpoint(u, v, c, d, sideC, sideD);
    if (!near && metBefore)
        near = t <= 0.5 ? c : d;
    if (near) {
        splitChains(owners, u, v, *near);
        m_pieces.push_back({*near, v, owners});
        m_pieces.push_back({u, *near, owners});
        return;
    }
    const Point3& pc = m_mesh.vertex(c);
    const Point3& pd = m_mesh.vertex(d);
    const Point3 crossing{pc.x + t * (pd.x - pc.x), pc.y + t * (pd.y - pc.y),
                          pc.z + t * (pd.z - pc.z)};

    MeshLocation where;
    std::optional<std::uint32_t> w = crossingVertex(crossing, crossed, where);
    requireEdgeInZone(c, d);

    const ConstraintOwners::Owners crossedOwners = takeOwners(c, d);
    m_mesh.setConstrained(crossed, false);
    if (!w) {
        w = insertVertex(crossing, kIntersectionSource, where);
        ++m_intersections;
    }
    splitChains(crossedOwners, c, d, *w);
    splitChains(owners, u, v, *w);
    // Unmarked, c -> d may be an edge that only its constraint kept (when the crossing fell
    // on another vertex, or off c -> d): flip it if it is not locally Delaunay.
    if (const std::size_t unmarked = m_mesh.findEdge(c, d); unmarked != kNoHalfEdge) {
        std::vector<std::size_t> stack{unmarked};
        m_mesh.restoreDelaunay(stack);
    }
    // A stack: c -> d is restored first, then u -> v goes on through w.
    m_pieces.push_back({*w, v, owners});
    m_pieces.push_back({u, *w, owners});
    m_pieces.push_back({*w, d, crossedOwners});
    m_pieces.push_back({c, *w, crossedOwners});
}

std::optional<std::uint32_t> ConstraintInserter::crossingVertex(const Point3& crossing,
                                                                std::size_t crossed,
                                                                MeshLocation& where) {
    // Found, and for a zone's inserter checked, before anything changes: a refusal leaves
    // the mesh as it was.
    where = m_mesh.locate({crossing.x, crossing.y}, crossed / 3);
    if (where.kind == MeshLocation::Kind::OutsideHull)
        throw std::logic_error("insertConstraints: a crossing lies outside the convex hull");
    std::optional<std::uint32_t> w;
    if (where.kind == MeshLocation::Kind::OnVertex)
        w = where.vertex;
    else
        w = vertexWithinRounding(crossing, where.halfEdge / 3);
    if (w) {
        m_mesh.rememberTriangle(*w, where.halfEdge / 3);
    } else {
        m_mesh.requireInsertable(where);
        if (where.kind == MeshLocation::Kind::OnEdge && m_mesh.isConstrained(where.halfEdge))
            requireEdgeInZone(m_mesh.from(where.halfEdge), m_mesh.to(where.halfEdge));
    }
    return w;
}

// c or d when it lies within rounding (kSnapUlps) of the line through u and v.
std::optional<std::uint32_t> ConstraintInserter::nearEndpoint(std::uint32_t u, std::uint32_t v,
                                                              std::uint32_t c, std::uint32_t d,
                                                              double sideC, double sideD) const {
    const Point2 pu = m_mesh.xy(u);
    const Point2 pv = m_mesh.xy(v);
    const Point2 pc = m_mesh.xy(c);
    const Point2 pd = m_mesh.xy(d);
    const double magnitude =
        std::max({std::fabs(pu.x), std::fabs(pu.y), std::fabs(pv.x), std::fabs(pv.y),
                  std::fabs(pc.x), std::fabs(pc.y), std::fabs(pd.x), std::fabs(pd.y)});
    const double tolerance = kSnapUlps * std::numeric_limits<double>::epsilon() * magnitude *
                             std::hypot(pv.x - pu.x, pv.y - pu.y);
    if (std::fabs(sideC) <= tolerance && std::fabs(sideC) <= std::fabs(sideD))
        return c;
    if (std::fabs(sideD) <= tolerance)
        return d;
    return std::nullopt;
}

// A crossing within rounding of a vertex of the triangle it falls in (an earlier crossing, most
// often, where several segments pass through one point) is that vertex.
std::optional<std::uint32_t> ConstraintInserter::vertexWithinRounding(const Point3& p,
                                                                      std::size_t triangle) const {
    for (std::size_t i = 0; i < 3; ++i) {
        const std::uint32_t corner = m_mesh.from(3 * triangle + i);
        const Point2 q = m_mesh.xy(corner);
        const double magnitude =
            std::max({std::fabs(p.x), std::fabs(p.y), std::fabs(q.x), std::fabs(q.y)});
        const double tolerance = kSnapUlps * std::numeric_limits<double>::epsilon() * magnitude;
        if (std::fabs(q.x - p.x) <= tolerance && std::fabs(q.y - p.y) <= tolerance)
            return corner;
    }
    return std::nullopt;
}

void ConstraintInserter::absorb(ConstraintInserter& zone) {
    // In any order: each removal is of a different edge.
    for (const std::uint64_t key : zone.m_takenShared)
        static_cast<void>(
            m_owners.take(static_cast<std::uint32_t>(key >> 32U), static_cast<std::uint32_t>(key)));
    m_owners.addAll(zone.m_owners);
    zone.m_chainEdits.applyTo(*m_chains);
    m_addedPoints += zone.m_addedPoints;
    m_intersections += zone.m_intersections;
    m_segmentsInserted += zone.m_segmentsInserted;
    m_mesh.makePendingFlips(zone.m_mesh);
}

void ConstraintInserter::compact(std::span<const SlotRange> unusedVertices,
                                 std::span<const SlotRange> unusedTriangles,
                                 std::vector<std::vector<std::uint32_t>>& vertexLists) {
    const std::vector<std::uint32_t> movedTo = m_mesh.compact(unusedVertices, unusedTriangles);
    const std::size_t kept = m_mesh.vertexCount();
    m_chains->renumber(kept, movedTo);
    renumberMoved(vertexLists, kept, movedTo);
}

void ConstraintInserter::finish(ConstrainedTin& tin) {
    tin.mesh = m_mesh.takeMesh();
    tin.constrained = m_mesh.takeFlags();
    tin.addedPoints = m_addedPoints;
    tin.intersections = m_intersections;
}

} // namespace terratin::detail

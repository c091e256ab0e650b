#include "segment_flips.hpp"

#include "terratin/geometry/predicates.hpp"

#include <stdexcept>

namespace terratin::detail {

namespace {

using Edge = CdtMesh::Edge;

// For w exactly on the line through u and v (w != u): whether w lies on the ray from u
// through v. Decided by comparisons alone, so exactly.
bool onRayFrom(const Point2& u, const Point2& v, const Point2& w) {
    if (u.x != v.x)
        return (w.x > u.x) == (v.x > u.x) && w.x != u.x;
    return (w.y > u.y) == (v.y > u.y) && w.y != u.y;
}

// Whether a and b lie strictly on opposite sides of the line through p and q.
bool strictlySeparates(const Point2& p, const Point2& q, const Point2& a, const Point2& b) {
    const double sideA = predicates::orient2d(p, q, a);
    const double sideB = predicates::orient2d(p, q, b);
    return (sideA < 0.0 && sideB > 0.0) || (sideA > 0.0 && sideB < 0.0);
}

// Sloan's loop: flip a crossing edge when its quadrilateral is strictly convex, else retry it
// later; one of the remaining crossing edges is always flippable, so the queue empties.
void flipCrossingsAway(CdtMesh& mesh, const Point2& pu, const Point2& pw, CrossedEdges& crossed) {
    std::vector<Edge>& queue = crossed.queue;
    queue.assign(crossed.edges.begin(), crossed.edges.end());
    std::size_t head = 0;
    std::size_t retriesInARow = 0; // a whole round of them would mean the theorem failed us
    while (head < queue.size()) {
        const Edge edge = queue[head++];
        const std::size_t h = mesh.find(edge);
        const std::size_t g = h == kNoHalfEdge ? kNoHalfEdge : mesh.twin(h);
        if (g == kNoHalfEdge)
            throw std::logic_error("insertConstraints: a crossed edge vanished");
        const std::uint32_t c = mesh.from(previousHalfEdge(h));
        const std::uint32_t d = mesh.from(previousHalfEdge(g));
        const Point2 pc = mesh.xy(c);
        const Point2 pd = mesh.xy(d);
        if (!strictlySeparates(pc, pd, mesh.xy(edge.a), mesh.xy(edge.b))) {
            queue.push_back(edge);
            if (++retriesInARow > queue.size() - head)
                throw std::logic_error("insertConstraints: no crossed edge can be flipped");
            continue;
        }
        retriesInARow = 0;
        mesh.flipAndRecord(h, g, crossed.touched);
        if (strictlySeparates(pu, pw, pc, pd)) {
            const std::size_t diagonal = crossed.touched[crossed.touched.size() - 5];
            queue.push_back({mesh.from(diagonal), mesh.to(diagonal), diagonal});
        }
    }
}

} // namespace

SegmentStart findSegmentStart(const CdtMesh& mesh, std::uint32_t u, std::uint32_t v) {
    const Point2 pu = mesh.xy(u);
    const Point2 pv = mesh.xy(v);
    SegmentStart start;
    bool found = false;
    const auto onSegment = [&](std::uint32_t w, double orientation) {
        return w == v || (orientation == 0.0 && onRayFrom(pu, pv, mesh.xy(w)));
    };
    mesh.forEachHalfEdgeAround(u, [&](std::size_t h) {
        if (mesh.from(h) != u)
            return false; // the hull edge arriving at u: its vertex was seen as p2 below
        const std::uint32_t p1 = mesh.to(h);
        const std::uint32_t p2 = mesh.from(previousHalfEdge(h));
        const double o1 = predicates::orient2d(pu, pv, mesh.xy(p1));
        const double o2 = predicates::orient2d(pu, pv, mesh.xy(p2));
        if (onSegment(p1, o1))
            start = {SegmentStart::Kind::AlongEdge, h, p1};
        else if (onSegment(p2, o2))
            start = {SegmentStart::Kind::AlongEdge, previousHalfEdge(h), p2};
        else if (o1 < 0.0 && o2 > 0.0)
            start = {SegmentStart::Kind::IntoTriangle, h, 0};
        else
            return false;
        found = true;
        return true;
    });
    if (!found)
        throw std::logic_error("insertConstraints: no triangle around a vertex faces the segment");
    return start;
}

std::size_t walkCrossedEdges(const CdtMesh& mesh, std::uint32_t u, std::uint32_t v,
                             const SegmentStart& start, CrossedEdges& crossed) {
    crossed.edges.clear();
    crossed.entries.clear();
    const Point2 pu = mesh.xy(u);
    const Point2 pv = mesh.xy(v);
    // In the first triangle (u, right, left) the segment leaves through right -> left; each
    // exit half-edge runs from the vertex right of the segment to the one left of it.
    std::size_t exit = nextHalfEdge(start.halfEdge);
    // A view must own every triangle the segment crosses: they are all rewritten. Each is
    // checked before the walk reads through it.
    mesh.requireOwned(start.halfEdge / 3);
    for (;;) {
        if (mesh.isConstrained(exit))
            return exit;
        crossed.edges.push_back({mesh.from(exit), mesh.to(exit), exit});
        const std::size_t entry = mesh.twin(exit);
        if (entry == kNoHalfEdge)
            throw std::logic_error("insertConstraints: segment walk left the convex hull");
        mesh.requireOwned(entry / 3);
        crossed.entries.push_back(entry);
        // entry runs left -> right; w is the vertex opposite it.
        const std::uint32_t w = mesh.from(previousHalfEdge(entry));
        const double side = w == v ? 0.0 : predicates::orient2d(pu, pv, mesh.xy(w));
        if (side == 0.0) {
            crossed.end = w;
            return kNoHalfEdge;
        }
        exit = side > 0.0 ? nextHalfEdge(entry) : previousHalfEdge(entry);
    }
}

std::size_t flipSegmentIn(CdtMesh& mesh, std::uint32_t u, CrossedEdges& crossed) {
    crossed.touched.clear();
    flipCrossingsAway(mesh, mesh.xy(u), mesh.xy(crossed.end), crossed);
    const std::size_t segment = mesh.findEdge(u, crossed.end);
    if (segment == kNoHalfEdge)
        throw std::logic_error("insertConstraints: flips did not make the segment an edge");
    mesh.setConstrained(segment, true);
    mesh.restoreDelaunay(crossed.touched);
    return mesh.findEdge(u, crossed.end);
}

} // namespace terratin::detail

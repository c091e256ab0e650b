#include "symbolic_predicates.hpp"

#include <algorithm>
#include <array>
#include <utility>

namespace terratin::detail {

int SymbolicPredicates::orientSymbolic(VertexId a, VertexId b, VertexId c) const {
    const int symbolicCount = !isFinite(a) + !isFinite(b) + !isFinite(c);
    if (symbolicCount == 2) {
        // Rotate (orientation is invariant under rotation) so the finite vertex comes last;
        // orient(p-2, p-1, q) = +1 because u1 x u2 = e2 - e1 < 0 dominates (see the header).
        const VertexId first = isFinite(a) ? b : (isFinite(b) ? c : a);
        return first == farLeft() ? 1 : -1;
    }
    // Exactly one symbolic vertex s: rotate to (u, v, s). With s = R*d and R -> infinity,
    // orient(u, v, s) has the sign of (v - u) x d, which for d = (1, -e1) is minus, and for
    // d = (-1, e2) plus, the lexicographic height of v relative to u.
    VertexId u = a;
    VertexId v = b;
    VertexId s = c;
    if (!isFinite(a)) {
        u = b;
        v = c;
        s = a;
    } else if (!isFinite(b)) {
        u = c;
        v = a;
        s = b;
    }
    const int height = compareHeight(m_points[u], m_points[v]);
    return s == farRight() ? -height : height;
}

bool SymbolicPredicates::shouldFlipSymbolic(VertexId i, VertexId j, VertexId k, VertexId l) const {
    // k is finite (just inserted). Write incircle(i, j, k, l) for "l strictly inside the
    // circle through i, j, k". The determinant is alternating in its four arguments, and a
    // symbolic point s is outside every circle through less symbolic points:
    // incircle(x, y, z, s) = -orient(x, y, z) whenever that orientation is not zero.
    if (isFinite(i) && isFinite(j))
        return false; // l is symbolic: outside the finite circle (i, j, k).

    if (isFinite(l)) {
        // One symbolic vertex on the edge, three finite ones.
        if (!isFinite(i)) {
            // incircle(s, j, k, l) = -incircle(j, k, l, s) = orient(j, k, l): the quadrilateral
            // (s, l, j, k) is convex at j. If j, k, l are collinear, j lies between l and k, so l
            // is outside every circle through j and k: no flip either.
            return orient(j, k, l) > 0;
        }
        // incircle(i, s, k, l) = incircle(i, k, l, s) = -orient(i, k, l) = orient(i, l, k).
        return orient(i, l, k) > 0;
    }

    // Two symbolic vertices: one on the edge, the other opposite (l). p-2 is the more symbolic.
    if (l == farLeft())
        // incircle(p-1, j, k, p-2) = -orient(p-1, j, k) < 0 and likewise with p-1 in second
        // place: (i, j, k) is a counter-clockwise triangle of the mesh.
        return false;
    if (i == farLeft())
        // incircle(p-2, j, k, p-1) = -incircle(j, k, p-1, p-2) = orient(j, k, p-1).
        return orient(j, k, farRight()) > 0;
    // j == p-2: incircle(i, p-2, k, p-1) = incircle(i, k, p-1, p-2) = -orient(i, k, p-1).
    return orient(i, k, farRight()) < 0;
}

namespace {
// For collinear finite points x, y, z (x != y): true when z lies outside the segment [x, y].
bool outsideSegment(const Point2& z, const Point2& x, const Point2& y) {
    if (x.x != y.x)
        return z.x < std::min(x.x, y.x) || z.x > std::max(x.x, y.x);
    return z.y < std::min(x.y, y.y) || z.y > std::max(x.y, y.y);
}
} // namespace

int SymbolicPredicates::incircle(VertexId a, VertexId b, VertexId c, VertexId d) const {
    // A repeated vertex lies on any circle through it. The circum-circle method asks this of a
    // triangle that already has the tested point as a corner.
    if (a == b || a == c || a == d || b == c || b == d || c == d)
        return 0;
    if (isFinite(a) && isFinite(b) && isFinite(c) && isFinite(d))
        return predicates::incircleTieBroken(m_points[a], m_points[b], m_points[c], m_points[d]);
    // Move the most symbolic vertex (p-2 before p-1) to the end; each swap of two arguments
    // flips the determinant's sign.
    std::array<VertexId, 4> q{a, b, c, d};
    const VertexId most = (a == farLeft() || b == farLeft() || c == farLeft() || d == farLeft())
                              ? farLeft()
                              : farRight();
    int sign = 1;
    for (std::size_t i = 0; i < 3; ++i) {
        if (q[i] == most) {
            std::swap(q[i], q[i + 1]);
            sign = -sign;
        }
    }
    // The symbolic point is outside every circle through less symbolic points:
    // incircle(x, y, z, s) = -orient(x, y, z).
    const int orientation = orient(q[0], q[1], q[2]);
    if (orientation != 0)
        return -sign * orientation;
    // x, y, z finite and collinear: the determinant reduces to (side of s) * (t_y - t_x) *
    // (t_z - t_x) * (t_z - t_y) along the line, i.e. orient(x, y, s) times +1 when z lies
    // outside [x, y] and -1 when inside.
    const int side = orient(q[0], q[1], q[3]);
    return sign * side * (outsideSegment(m_points[q[2]], m_points[q[0]], m_points[q[1]]) ? 1 : -1);
}

} // namespace terratin::detail

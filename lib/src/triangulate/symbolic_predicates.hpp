#pragma once
/// @file
/// Exact predicates on vertex ids, including the two symbolic vertices of the auxiliary
/// triangle.
///
/// Notation. The finite vertices are 0..n-1 with local coordinates P[i]. The auxiliary
/// triangle is (p0, p-2, p-1) in counter-clockwise order, where p0 is the highest finite
/// point ("higher" = larger y, ties broken by larger x: the lexicographic order of de Berg et
/// al., Computational Geometry, 3rd ed., section 9.3) and p-1, p-2 are symbolic:
///
///     p-1 = R1 * (1, -e1),   p-2 = R2 * (-1, e2),   with 1 << R1 << R2 and 0 < e2 << e1 << 1,
///
/// i.e. p-1 is infinitely far to the right (and slightly down), p-2 infinitely farther to the
/// left (and slightly up). Every answer below is the limit of the exact predicate for this
/// realization, so all answers together are consistent with one real configuration of points:
/// the triangulation built from them is a true Delaunay triangulation of P u {p-1, p-2}, and
/// removing the triangles that touch p-1 or p-2 leaves a Delaunay triangulation of P covering
/// exactly its convex hull (each hull edge of P has an empty circle bulging outwards that
/// misses the far-away symbolic points). No finite auxiliary triangle gives that guarantee
/// for every input: near-collinear hull points defeat any fixed size.
///
/// The limits reduce to lexicographic comparisons:
///   orient(a, b, p-1) = -sign(height of b relative to a)
///   orient(a, b, p-2) = +sign(height of b relative to a)
///   orient(p-2, p-1, q) = +1 for every finite q
/// and p-1 lies outside every circle through three finite points, p-2 outside every circle
/// through three points of P u {p-1}. The flip rules in shouldFlip follow from these by the
/// antisymmetry of the in-circle determinant (derivation beside each case).

#include "terratin/geometry/point.hpp"
#include "terratin/geometry/predicates.hpp"

#include <cstdint>
#include <span>

namespace terratin::detail {

using VertexId = std::uint32_t;

/// Sign-only predicates over finite and symbolic vertex ids.
class SymbolicPredicates {
public:
    /// `points` are the finite vertices; ids points.size() and points.size() + 1 are the
    /// symbolic vertices p-1 (farRight()) and p-2 (farLeft()).
    explicit SymbolicPredicates(std::span<const Point2> points)
        : m_points(points.data()), m_count(static_cast<VertexId>(points.size())) {}

    [[nodiscard]] VertexId farRight() const { return m_count; }
    [[nodiscard]] VertexId farLeft() const { return m_count + 1; }
    [[nodiscard]] bool isFinite(VertexId v) const { return v < m_count; }
    [[nodiscard]] const Point2& point(VertexId v) const { return m_points[v]; }

    /// +1 when a, b, c turn counter-clockwise, -1 clockwise, 0 when collinear (only possible
    /// for three finite vertices).
    [[nodiscard]] int orient(VertexId a, VertexId b, VertexId c) const {
        if (a < m_count && b < m_count && c < m_count)
            return sign(predicates::orient2d(m_points[a], m_points[b], m_points[c]));
        return orientSymbolic(a, b, c);
    }

    /// Lawson's test for the edge (i, j) shared by the counter-clockwise triangles (i, j, k)
    /// and (j, i, l), where k is a finite vertex just inserted: true when l lies strictly inside
    /// the circumcircle of (i, j, k), so the edge must be flipped to (k, l). Four cocircular
    /// finite points are decided by predicates::incircleTieBroken, so that grids (cocircular
    /// everywhere) get the same diagonals whatever the insertion order.
    /// Precondition: (i, j) is not the edge p-1 p-2.
    [[nodiscard]] bool shouldFlip(VertexId i, VertexId j, VertexId k, VertexId l) const {
        if (i < m_count && j < m_count && l < m_count)
            return predicates::incircleTieBroken(m_points[i], m_points[j], m_points[k],
                                                 m_points[l]) > 0;
        return shouldFlipSymbolic(i, j, k, l);
    }

    /// Sign of the in-circle determinant of any four vertices (finite or symbolic): for a
    /// counter-clockwise (a, b, c), +1 when d lies strictly inside their circumcircle, -1
    /// outside (cocircular finite points as predicates::incircleTieBroken decides), 0 when a
    /// vertex repeats or four finite points are collinear. Slower than shouldFlip; for the
    /// circum-circle method's conflict test and for repairs, where the fourth point is not always
    /// the new one.
    [[nodiscard]] int incircle(VertexId a, VertexId b, VertexId c, VertexId d) const;

    /// For a counter-clockwise (a, b, c): true only when d lies strictly inside their
    /// circumcircle. With four finite vertices, a d too close to the circle for the
    /// floating-point filter counts as outside (no exact arithmetic); symbolic cases are exact.
    /// For the circum-circle method's conflict test, a hint whose misses the owner tags catch.
    [[nodiscard]] bool surelyInside(VertexId a, VertexId b, VertexId c, VertexId d) const {
        if (a < m_count && b < m_count && c < m_count && d < m_count)
            return predicates::incircleSurelyInside(m_points[a], m_points[b], m_points[c],
                                                    m_points[d]);
        return incircle(a, b, c, d) > 0;
    }

    /// +1 when q is higher than p (larger y, or equal y and larger x), -1 when lower, 0 when
    /// equal.
    static int compareHeight(const Point2& p, const Point2& q) {
        if (q.y != p.y)
            return q.y > p.y ? 1 : -1;
        if (q.x != p.x)
            return q.x > p.x ? 1 : -1;
        return 0;
    }

private:
    static int sign(double value) { return (value > 0.0) - (value < 0.0); }

    int orientSymbolic(VertexId a, VertexId b, VertexId c) const;
    bool shouldFlipSymbolic(VertexId i, VertexId j, VertexId k, VertexId l) const;

    const Point2* m_points;
    VertexId m_count;
};

} // namespace terratin::detail

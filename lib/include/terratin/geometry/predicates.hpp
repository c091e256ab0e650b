#pragma once
/// @file
/// Exact geometric predicates after J. R. Shewchuk, "Adaptive Precision Floating-Point
/// Arithmetic and Fast Robust Geometric Predicates", Discrete & Computational Geometry 18 (1997).
/// Each predicate returns a value whose SIGN is exactly that of the real-number determinant of
/// its double inputs (magnitude is only an approximation).
///
/// Preconditions: inputs are finite and no intermediate product overflows or underflows. That
/// holds when every coordinate is zero or has a magnitude between 1e-60 and 1e70: every input is
/// then a multiple of 2^-252, so every nonzero exact intermediate of the degree-4 incircle
/// determinant is a multiple of 2^-1008 (still a normal double), and none exceeds about 2^950.
/// orient2d (degree 2) tolerates far more, but one range is easier to state and to check. The
/// triangulator shifts coordinates to a local origin, so real inputs sit well inside it.
///
/// Structure: the first stage (a plain floating-point evaluation plus a forward error bound,
/// Shewchuk's stage A) is inline here because it decides almost every call (~100 million calls
/// per million points triangulated); the rarely needed adaptive stages live out of line in
/// predicates.cpp. Requires IEEE-754 double arithmetic in round-to-nearest-even, the default
/// mode, which terratin never changes. Compilers may contract the filter's products into fused
/// multiply-adds (GCC does in C++ when the target has FMA); that only removes roundings, so the
/// stage A bounds below still hold (the tests pass with -march=native -ffp-contract=fast).

#include "terratin/geometry/point.hpp"

#include <cmath>
#include <limits>

#if defined(__FAST_MATH__)
#error "terratin predicates rely on IEEE-754 rounding: do not compile with -ffast-math"
#endif

namespace terratin::predicates {

namespace detail {

/// Unit roundoff u = 2^-53: the relative error of one correctly rounded double operation
/// (half of numeric_limits::epsilon(), which is the spacing 2^-52 just above 1).
inline constexpr double kEpsilon = std::numeric_limits<double>::epsilon() / 2.0;

/// Stage A bound for orient2d (Shewchuk section 4): the filter's determinant suffers one
/// rounding per coordinate difference, per product and in the final subtraction, so its error is
/// at most 3u times the permanent |detLeft| + |detRight| to first order; the 16u^2 term covers the
/// second-order products of those roundings and the rounding made computing the bound itself.
inline constexpr double kOrient2dErrorBoundA = (3.0 + 16.0 * kEpsilon) * kEpsilon;

/// Stage A bound for incircle (Shewchuk section 4): each of the three lifted terms goes
/// through differences, products, the sum for the lift, the 2x2 minor and the product with the
/// lift, and the three terms are summed twice; following the roundings along that evaluation
/// order bounds the error by 10u times the permanent to first order, and 96u^2 covers
/// second-order terms and the rounding made computing the bound itself.
inline constexpr double kIncircleErrorBoundA = (10.0 + 96.0 * kEpsilon) * kEpsilon;

/// Stages B, C and D of orient2d; detSum is the permanent |detLeft| + |detRight| from stage A.
/// Out of line and not inlined so that the inline fast path stays small.
double orient2dAdaptive(const Point2& a, const Point2& b, const Point2& c, double detSum);

/// Stages B, C and D of incircle; permanent is the stage A error scale.
double incircleAdaptive(const Point2& a, const Point2& b, const Point2& c, const Point2& d,
                        double permanent);

/// The exact stage alone: orient2d's determinant evaluated exactly in expansion arithmetic,
/// returning its most significant component. Same sign contract as orient2d, no filter; many
/// times slower than the filtered path (docs/benchmarks.md). Exposed so that it can be verified
/// on every input, not only on the few that reach it through the filters.
double orient2dExact(const Point2& a, const Point2& b, const Point2& c);

/// The exact stage alone for incircle (see orient2dExact); slower still (docs/benchmarks.md).
double incircleExact(const Point2& a, const Point2& b, const Point2& c, const Point2& d);

} // namespace detail

/// Positive if a, b, c turn counter-clockwise, negative if clockwise, zero if collinear.
/// Coordinates in any consistent unit; the magnitude approximates twice the signed area.
/// O(1); no allocation; thread-safe.
inline double orient2d(const Point2& a, const Point2& b, const Point2& c) {
    const double detLeft = (a.x - c.x) * (b.y - c.y);
    const double detRight = (a.y - c.y) * (b.x - c.x);
    const double det = detLeft - detRight;
    const double detSum = std::fabs(detLeft) + std::fabs(detRight);
    // detSum == 0 means both products are exactly zero (no underflow, see the preconditions),
    // so det == 0 is exact: rows and columns of DEM grids are collinear that way, and that
    // common case must not fall through to the adaptive stages.
    if (std::fabs(det) > detail::kOrient2dErrorBoundA * detSum || detSum == 0.0) [[likely]] {
        return det;
    }
    return detail::orient2dAdaptive(a, b, c, detSum);
}

namespace detail {

/// Stage A of incircle: the determinant in plain floating point, and in `permanent` the scale
/// its error bound is a multiple of (see kIncircleErrorBoundA).
inline double incircleStageA(const Point2& a, const Point2& b, const Point2& c, const Point2& d,
                             double& permanent) {
    const double adx = a.x - d.x;
    const double bdx = b.x - d.x;
    const double cdx = c.x - d.x;
    const double ady = a.y - d.y;
    const double bdy = b.y - d.y;
    const double cdy = c.y - d.y;

    const double bdxcdy = bdx * cdy;
    const double cdxbdy = cdx * bdy;
    const double aLift = adx * adx + ady * ady;

    const double cdxady = cdx * ady;
    const double adxcdy = adx * cdy;
    const double bLift = bdx * bdx + bdy * bdy;

    const double adxbdy = adx * bdy;
    const double bdxady = bdx * ady;
    const double cLift = cdx * cdx + cdy * cdy;

    permanent = (std::fabs(bdxcdy) + std::fabs(cdxbdy)) * aLift +
                (std::fabs(cdxady) + std::fabs(adxcdy)) * bLift +
                (std::fabs(adxbdy) + std::fabs(bdxady)) * cLift;
    return aLift * (bdxcdy - cdxbdy) + bLift * (cdxady - adxcdy) + cLift * (adxbdy - bdxady);
}

} // namespace detail

/// For a, b, c in counter-clockwise order: positive if d lies strictly inside their circumcircle,
/// negative if strictly outside, zero if the four points are cocircular. The sign flips when
/// a, b, c are clockwise. The function is alternating: swapping any two arguments flips the sign.
/// O(1); no allocation; thread-safe.
inline double incircle(const Point2& a, const Point2& b, const Point2& c, const Point2& d) {
    double permanent = 0.0;
    const double det = detail::incircleStageA(a, b, c, d, permanent);
    // permanent == 0 means each lifted term has a zero lift (a point equal to d) or a minor
    // whose two products are exactly zero, so det == 0 is exact.
    if (std::fabs(det) > detail::kIncircleErrorBoundA * permanent || permanent == 0.0) [[likely]] {
        return det;
    }
    return detail::incircleAdaptive(a, b, c, d, permanent);
}

namespace detail {
/// The sign incircleTieBroken gives four cocircular points (out of line: rare outside grids).
int cocircularTieSign(const Point2& a, const Point2& b, const Point2& c, const Point2& d);
} // namespace detail

/// For a, b, c in counter-clockwise order: +1 if d lies inside their circumcircle, -1 if
/// outside, like incircle, except that four cocircular points get the sign of a symbolic
/// perturbation instead of 0. Each point is lifted by an infinitesimal, the lexicographically
/// largest point ((x, y) order) by the largest one, as in CGAL's Delaunay_triangulation_2 and
/// Devillers, "Perturbations for Delaunay and weighted Delaunay 3D triangulations" (2011).
/// The answer depends only on the four coordinates, so every quadrilateral of cocircular points
/// has exactly one legal diagonal and the Delaunay triangulation is unique: every insertion
/// order, thread count and method then builds the same one (DEM grids are cocircular at every
/// cell). 0 only for degenerate input (a repeated point, or all four collinear).
inline int incircleTieBroken(const Point2& a, const Point2& b, const Point2& c, const Point2& d) {
    const double det = incircle(a, b, c, d);
    if (det != 0.0) [[likely]]
        return det > 0.0 ? 1 : -1;
    return detail::cocircularTieSign(a, b, c, d);
}

/// For a, b, c in counter-clockwise order: true when stage A alone proves d strictly inside
/// their circumcircle. False when d is outside, on the circle, or too close to it for stage A
/// to tell: a one-sided test for heuristics that must stay cheap on near-cocircular points
/// (points on an arc send nearly every exact incircle call to the adaptive stages).
inline bool incircleSurelyInside(const Point2& a, const Point2& b, const Point2& c,
                                 const Point2& d) {
    double permanent = 0.0;
    const double det = detail::incircleStageA(a, b, c, d, permanent);
    return det > detail::kIncircleErrorBoundA * permanent;
}

} // namespace terratin::predicates

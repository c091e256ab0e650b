/// @file
/// Adaptive stages of the exact predicates (stage A, the filter, is inline in predicates.hpp).
///
/// Reference: J. R. Shewchuk, "Adaptive Precision Floating-Point Arithmetic and Fast Robust
/// Geometric Predicates", Discrete & Computational Geometry 18:305-363 (1997). This file is an
/// implementation written from the paper's algorithms, not a copy of its predicates.c. The
/// expansions it computes with, and the notation (u, expansion), are in
/// expansion_arithmetic.hpp.
///
/// Stages, each tried only when the previous one cannot decide the sign:
///   A  plain double evaluation + forward error bound (predicates.hpp);
///   B  the exact determinant of the *rounded* coordinate differences, which ignores only the
///      rounding errors ("tails") of the differences; exact as is when all tails are zero;
///   C  B's estimate plus the first-order tail terms in doubles, with a second-order bound;
///   D  the exact determinant of the exact differences (the orient2dExact / incircleExact).
/// Stage D costs far more than B and C; B is reached by exactly degenerate inputs (collinear
/// grid points, cocircular grid squares), whose differences are nearly always exact, so B
/// settles them. The error bounds below are those derived in the paper, section 4.
///
/// Requirements checked at compile time: IEEE-754 binary64 without excess precision (no x87)
/// and without -ffast-math (predicates.hpp). Round-to-nearest-even must be the rounding mode at
/// run time (the default); Fast-Expansion-Sum's proof needs the round-to-even tie break.

#include "terratin/geometry/predicates.hpp"

#include "expansion_arithmetic.hpp"
#include "lattice_incircle.hpp"

#include <algorithm>
#include <array>
#include <cfloat>
#include <cmath>
#include <cstddef>
#include <limits>

static_assert(std::numeric_limits<double>::is_iec559 && std::numeric_limits<double>::digits == 53,
              "the predicates need IEEE-754 binary64 doubles");
#if !defined(FLT_EVAL_METHOD) || FLT_EVAL_METHOD != 0
#error "the predicates need every double operation rounded to double (no x87 excess precision)"
#endif

namespace terratin::predicates::detail {
namespace {

// ---------------------------------------------------------------------------------------------
// Error bounds of the adaptive stages, as multiples of the stage A permanent (kEpsilon = u);
// kResultErrorBound alone multiplies |estimate| instead.

/// Stage C starts from the double estimate of stage B's expansion and adds a correction to it;
/// this, times |estimate|, covers the rounding of that estimate and of the final addition
/// (first order 3u), with 8u^2 for second order.
constexpr double kResultErrorBound = (3.0 + 8.0 * kEpsilon) * kEpsilon;

/// orient2d stage B: B differs from the true determinant only by the terms involving the
/// difference tails, each tail at most u times its difference; each product has two such
/// factors, giving 2u times the permanent to first order; 12u^2 covers second order and the
/// rounding of B's estimate.
constexpr double kOrient2dErrorBoundB = (2.0 + 12.0 * kEpsilon) * kEpsilon;

/// orient2d stage C: after adding the first-order tail terms, what is left is the product of two
/// tails (u^2 times the permanent) and the roundings of the correction's evaluation (u times
/// terms already of size 2u); 9u^2 bounds their sum and 64u^3 the higher orders.
constexpr double kOrient2dErrorBoundC = (9.0 + 64.0 * kEpsilon) * kEpsilon * kEpsilon;

/// incircle stage B: the lift (degree 2) and minor (degree 2) each carry two differences whose
/// tails are ignored, 4u times the permanent to first order; 48u^2 covers the rest.
constexpr double kIncircleErrorBoundB = (4.0 + 48.0 * kEpsilon) * kEpsilon;

/// incircle stage C: second-order tail products and the roundings of the first-order
/// correction, whose sum the paper bounds by 44u^2 times the permanent; 576u^3 for the rest.
constexpr double kIncircleErrorBoundC = (44.0 + 576.0 * kEpsilon) * kEpsilon * kEpsilon;

// ---------------------------------------------------------------------------------------------
// incircle stage B helper: the lifted term (dx^2 + dy^2) * minor for rounded differences.

Expansion<32> liftedTerm(const Expansion<4>& minor, double dx, double dy) {
    return sum(scale(scale(minor, dx), dx), scale(scale(minor, dy), dy));
}

} // namespace

double orient2dExact(const Point2& a, const Point2& b, const Point2& c) {
    const Expansion<2> acx = exactDifference(a.x, c.x);
    const Expansion<2> bcx = exactDifference(b.x, c.x);
    const Expansion<2> acy = exactDifference(a.y, c.y);
    const Expansion<2> bcy = exactDifference(b.y, c.y);
    return difference(product(acx, bcy), product(acy, bcx)).mostSignificant();
}

double incircleExact(const Point2& a, const Point2& b, const Point2& c, const Point2& d) {
    const Expansion<2> adx = exactDifference(a.x, d.x);
    const Expansion<2> bdx = exactDifference(b.x, d.x);
    const Expansion<2> cdx = exactDifference(c.x, d.x);
    const Expansion<2> ady = exactDifference(a.y, d.y);
    const Expansion<2> bdy = exactDifference(b.y, d.y);
    const Expansion<2> cdy = exactDifference(c.y, d.y);

    // det = aLift * (bdx cdy - cdx bdy) + bLift * (cdx ady - adx cdy) + cLift * (adx bdy - bdx ady)
    const auto aTerm = product(sum(product(adx, adx), product(ady, ady)),
                               difference(product(bdx, cdy), product(cdx, bdy)));
    const auto bTerm = product(sum(product(bdx, bdx), product(bdy, bdy)),
                               difference(product(cdx, ady), product(adx, cdy)));
    const auto cTerm = product(sum(product(cdx, cdx), product(cdy, cdy)),
                               difference(product(adx, bdy), product(bdx, ady)));
    return sum(sum(aTerm, bTerm), cTerm).mostSignificant();
}

[[gnu::noinline]] double orient2dAdaptive(const Point2& a, const Point2& b, const Point2& c,
                                          double detSum) {
    const double acx = a.x - c.x;
    const double bcx = b.x - c.x;
    const double acy = a.y - c.y;
    const double bcy = b.y - c.y;

    // Stage B.
    const Expansion<4> exactRounded =
        twoTwoDifference(exactProduct(acx, bcy), exactProduct(acy, bcx));
    double det = exactRounded.estimate();
    double errorBound = kOrient2dErrorBoundB * detSum;
    if (det > errorBound || -det > errorBound) {
        return det;
    }

    const double acxTail = twoDiffTail(a.x, c.x, acx);
    const double bcxTail = twoDiffTail(b.x, c.x, bcx);
    const double acyTail = twoDiffTail(a.y, c.y, acy);
    const double bcyTail = twoDiffTail(b.y, c.y, bcy);
    if (acxTail == 0.0 && acyTail == 0.0 && bcxTail == 0.0 && bcyTail == 0.0) {
        // The differences were exact, so stage B's expansion is the exact determinant; its
        // most significant component carries the exact sign (the estimate could round to 0).
        return exactRounded.mostSignificant();
    }

    // Stage C.
    errorBound = kOrient2dErrorBoundC * detSum + kResultErrorBound * std::fabs(det);
    det += (acx * bcyTail + bcy * acxTail) - (acy * bcxTail + bcx * acyTail);
    if (det > errorBound || -det > errorBound) {
        return det;
    }

    // Stage D.
    return orient2dExact(a, b, c);
}

namespace {

// Whether the four points are the corners of a rectangle with sides parallel to the axes, in
// any order: each shares its x with exactly one other point and its y with another.
bool axisParallelRectangle(const Point2& a, const Point2& b, const Point2& c, const Point2& d) {
    const Point2* sameX = nullptr;
    const Point2* sameY = nullptr;
    const Point2* opposite = nullptr;
    for (const Point2* p : {&b, &c, &d}) {
        const bool x = p->x == a.x;
        const bool y = p->y == a.y;
        if (x && y)
            return false;
        const Point2*& role = x ? sameX : y ? sameY : opposite;
        if (role != nullptr)
            return false;
        role = p;
    }
    return sameX->y == opposite->y && sameY->x == opposite->x;
}

/// incircle's coordinate differences a - d, b - d, c - d: rounded, or their tails.
struct IncircleDifferences {
    double adx, bdx, cdx, ady, bdy, cdy;
};

/// incircle stage C's correction: the first-order change of sum(lift * minor) when each
/// rounded difference `r` gains its tail `t`: d(lift) * minor + lift * d(minor), with
/// d(dx^2 + dy^2) = 2 (dx dxTail + dy dyTail).
inline double incircleTailTerms(const IncircleDifferences& r, const IncircleDifferences& t) {
    return ((r.adx * r.adx + r.ady * r.ady) *
                ((r.bdx * t.cdy + r.cdy * t.bdx) - (r.bdy * t.cdx + r.cdx * t.bdy)) +
            2.0 * (r.adx * t.adx + r.ady * t.ady) * (r.bdx * r.cdy - r.bdy * r.cdx)) +
           ((r.bdx * r.bdx + r.bdy * r.bdy) *
                ((r.cdx * t.ady + r.ady * t.cdx) - (r.cdy * t.adx + r.adx * t.cdy)) +
            2.0 * (r.bdx * t.bdx + r.bdy * t.bdy) * (r.cdx * r.ady - r.cdy * r.adx)) +
           ((r.cdx * r.cdx + r.cdy * r.cdy) *
                ((r.adx * t.bdy + r.bdy * t.adx) - (r.ady * t.bdx + r.bdx * t.ady)) +
            2.0 * (r.cdx * t.cdx + r.cdy * t.cdy) * (r.adx * r.bdy - r.ady * r.bdx));
}

} // namespace

[[gnu::noinline]] double incircleAdaptive(const Point2& a, const Point2& b, const Point2& c,
                                          const Point2& d, double permanent) {
    // The corners of a raster cell reach this stage on every test (stage A cannot tell their
    // zero from rounding); a rectangle's corners are exactly cocircular.
    if (axisParallelRectangle(a, b, c, d))
        return 0.0;
    const double adx = a.x - d.x;
    const double bdx = b.x - d.x;
    const double cdx = c.x - d.x;
    const double ady = a.y - d.y;
    const double bdy = b.y - d.y;
    const double cdy = c.y - d.y;
    const double adxTail = twoDiffTail(a.x, d.x, adx);
    const double bdxTail = twoDiffTail(b.x, d.x, bdx);
    const double cdxTail = twoDiffTail(c.x, d.x, cdx);
    const double adyTail = twoDiffTail(a.y, d.y, ady);
    const double bdyTail = twoDiffTail(b.y, d.y, bdy);
    const double cdyTail = twoDiffTail(c.y, d.y, cdy);
    const bool exactDifferences = adxTail == 0.0 && bdxTail == 0.0 && cdxTail == 0.0 &&
                                  adyTail == 0.0 && bdyTail == 0.0 && cdyTail == 0.0;
    // Other cocircular cell centres (a cavity's larger triangles in a grid) differ by lattice
    // steps.
    if (exactDifferences)
        if (const std::optional<double> sign = latticeIncircle(adx, ady, bdx, bdy, cdx, cdy))
            return *sign;

    // Stage B.
    const Expansion<4> bc = twoTwoDifference(exactProduct(bdx, cdy), exactProduct(cdx, bdy));
    const Expansion<4> ca = twoTwoDifference(exactProduct(cdx, ady), exactProduct(adx, cdy));
    const Expansion<4> ab = twoTwoDifference(exactProduct(adx, bdy), exactProduct(bdx, ady));
    const Expansion<96> exactRounded =
        sum(sum(liftedTerm(bc, adx, ady), liftedTerm(ca, bdx, bdy)), liftedTerm(ab, cdx, cdy));
    double det = exactRounded.estimate();
    double errorBound = kIncircleErrorBoundB * permanent;
    if (det > errorBound || -det > errorBound) {
        return det;
    }

    if (exactDifferences) {
        // Stage B's expansion is the exact determinant (see orient2d).
        return exactRounded.mostSignificant();
    }

    // Stage C.
    errorBound = kIncircleErrorBoundC * permanent + kResultErrorBound * std::fabs(det);
    det += incircleTailTerms({adx, bdx, cdx, ady, bdy, cdy},
                             {adxTail, bdxTail, cdxTail, adyTail, bdyTail, cdyTail});
    if (det > errorBound || -det > errorBound) {
        return det;
    }

    // Stage D.
    return incircleExact(a, b, c, d);
}

namespace {
bool lexicographicallyLess(const Point2& p, const Point2& q) {
    return p.x < q.x || (p.x == q.x && p.y < q.y);
}

int signOf(double value) {
    return (value > 0.0) - (value < 0.0);
}

/// The sign of the derivative of incircle(a, b, c, d) by the lift of `point` (one of the four,
/// by address). By the alternation, moving d outwards lowers incircle at the rate
/// orient(a, b, c); the others follow by swapping them with d.
int liftDerivativeSign(const Point2* point, const Point2& a, const Point2& b, const Point2& c,
                       const Point2& d) {
    if (point == &d)
        return -signOf(orient2d(a, b, c));
    if (point == &c)
        return signOf(orient2d(a, b, d));
    if (point == &b)
        return signOf(orient2d(a, d, c));
    return signOf(orient2d(d, b, c));
}
} // namespace

int cocircularTieSign(const Point2& a, const Point2& b, const Point2& c, const Point2& d) {
    if (a == b || a == c || a == d || b == c || b == d || c == d)
        return 0; // a repeated point lies on every circle through it
    // The lifted determinant is linear in each lift, so the perturbed one is
    // incircle + sum(eps_i * dIncircle/dLift_i), and its sign is that of the first nonzero
    // derivative, largest point first. Four distinct cocircular points have no three collinear,
    // so the largest point decides; the others matter only for four collinear points.
    std::array<const Point2*, 4> points{&a, &b, &c, &d};
    std::iter_swap(points.begin(), std::max_element(points.begin(), points.end(),
                                                    [](const Point2* p, const Point2* q) {
                                                        return lexicographicallyLess(*p, *q);
                                                    }));
    if (const int sign = liftDerivativeSign(points[0], a, b, c, d); sign != 0) [[likely]]
        return sign;
    std::sort(points.begin() + 1, points.end(),
              [](const Point2* p, const Point2* q) { return lexicographicallyLess(*q, *p); });
    for (std::size_t i = 1; i < points.size(); ++i)
        if (const int sign = liftDerivativeSign(points[i], a, b, c, d); sign != 0)
            return sign;
    return 0;
}

} // namespace terratin::predicates::detail

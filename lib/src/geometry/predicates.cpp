/// @file
/// Adaptive stages of the exact predicates (stage A, the filter, is inline in predicates.hpp).
///
/// Reference: J. R. Shewchuk, "Adaptive Precision Floating-Point Arithmetic and Fast Robust
/// Geometric Predicates", Discrete & Computational Geometry 18:305-363 (1997). This file is an
/// implementation written from the paper's algorithms, not a copy of its predicates.c.
///
/// Notation. u = 2^-53 is the unit roundoff. An *expansion* is an unevaluated sum of doubles
/// e[0] + e[1] + ... + e[n-1], stored from smallest to largest magnitude, whose components do
/// not overlap (each one's lowest set bit lies above the highest set bit of the one before), so
/// its value is exact and its sign is the sign of its largest component. Every routine here
/// eliminates zero components, so the last component is the most significant one (an
/// expansion of value zero is the single component 0).
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
// Error-free transformations (paper section 2): each returns head = fl(exact) and the exact
// rounding error as tail, so that head + tail equals the exact result.

struct TwoTerm {
    double head;
    double tail;
};

/// Knuth's Two-Sum: any a, b.
inline TwoTerm twoSum(double a, double b) {
    const double sum = a + b;
    const double bVirtual = sum - a;
    const double aVirtual = sum - bVirtual;
    return {sum, (a - aVirtual) + (b - bVirtual)};
}

/// Dekker's Fast-Two-Sum: needs |a| >= |b| (or a == 0); three operations instead of six.
inline TwoTerm fastTwoSum(double a, double b) {
    const double sum = a + b;
    return {sum, b - (sum - a)};
}

/// Two-Diff: Two-Sum of a and -b, written out so that no negation is needed.
inline TwoTerm twoDiff(double a, double b) {
    const double diff = a - b;
    const double bVirtual = a - diff;
    const double aVirtual = diff + bVirtual;
    return {diff, (a - aVirtual) + (bVirtual - b)};
}

/// The rounding error of diff = fl(a - b), for a diff computed elsewhere.
inline double twoDiffTail(double a, double b, double diff) {
    const double bVirtual = a - diff;
    const double aVirtual = diff + bVirtual;
    return (a - aVirtual) + (bVirtual - b);
}

// Where the target has a hardware fused multiply-add, fma(a, b, -p) is the exact error of
// p = fl(a * b) in one instruction. Without one, std::fma would be a slow library call, so
// Dekker's splitting is used instead; it is only safe where the compiler cannot contract
// a * b - c into an fma, and that holds precisely when the target has no fma instruction.
#if defined(FP_FAST_FMA) || defined(__FMA__) || defined(__ARM_FEATURE_FMA)

/// Two-Product: head = fl(a * b), tail its exact rounding error.
inline TwoTerm twoProduct(double a, double b) {
    const double product = a * b;
    return {product, std::fma(a, b, -product)};
}

#else

/// Dekker's splitting constant 2^27 + 1: splits a 53-bit significand into a high part of 26
/// bits and a low part of at most 26 bits (ceil(53 / 2) = 27), so that products of the
/// halves fit in 53 bits and are exact.
constexpr double kSplitter = 134217729.0;

inline TwoTerm split(double a) {
    const double scaled = kSplitter * a;
    const double aBig = scaled - a;
    const double aHigh = scaled - aBig;
    return {aHigh, a - aHigh};
}

/// Two-Product: head = fl(a * b), tail its exact rounding error.
inline TwoTerm twoProduct(double a, double b) {
    const double product = a * b;
    const TwoTerm aParts = split(a);
    const TwoTerm bParts = split(b);
    // Each partial product below is exact, and each subtraction is exact because it removes the
    // leading bits of the running error (Dekker 1971; paper section 2.5).
    const double err1 = product - aParts.head * bParts.head;
    const double err2 = err1 - aParts.tail * bParts.head;
    const double err3 = err2 - aParts.head * bParts.tail;
    return {product, aParts.tail * bParts.tail - err3};
}

#endif

// ---------------------------------------------------------------------------------------------
// Expansions with a compile-time capacity: every size below is the worst case, so no path
// allocates and the stack use of each stage is fixed.

template <std::size_t Capacity> struct Expansion {
    // Only [0, size) is meaningful; left uninitialised because zeroing would cost more than the
    // arithmetic on the short expansions met in practice.
    std::array<double, Capacity> terms;
    std::size_t size = 0;

    double mostSignificant() const { return terms[size - 1]; }

    /// A double approximation of the value: the components summed from the smallest up. Its
    /// sign is not guaranteed when the value is tiny; mostSignificant() is exact in sign.
    double estimate() const {
        double sum = terms[0];
        for (std::size_t i = 1; i < size; ++i) {
            sum += terms[i];
        }
        return sum;
    }
};

/// Appends a component unless it is zero (zero elimination).
inline void appendNonZero(double value, double* h, std::size_t& hSize) {
    if (value != 0.0) {
        h[hSize++] = value;
    }
}

/// Ends an expansion: the last running sum is its most significant component; a value of zero
/// keeps one zero component so that every expansion has at least one.
inline void appendLast(double value, double* h, std::size_t& hSize) {
    if (value != 0.0 || hSize == 0) {
        h[hSize++] = value;
    }
}

/// Grow-Expansion (paper Theorem 10): h = e + b, at most eSize + 1 components.
std::size_t growExpansion(const double* e, std::size_t eSize, double b, double* h) {
    std::size_t hSize = 0;
    double running = b;
    for (std::size_t i = 0; i < eSize; ++i) {
        const TwoTerm sum = twoSum(running, e[i]);
        appendNonZero(sum.tail, h, hSize);
        running = sum.head;
    }
    appendLast(running, h, hSize);
    return hSize;
}

/// Scale-Expansion (paper Theorem 19): h = e * b, at most 2 * eSize components.
std::size_t scaleExpansion(const double* e, std::size_t eSize, double b, double* h) {
    std::size_t hSize = 0;
    const TwoTerm first = twoProduct(e[0], b);
    appendNonZero(first.tail, h, hSize);
    double running = first.head;
    for (std::size_t i = 1; i < eSize; ++i) {
        const TwoTerm product = twoProduct(e[i], b);
        const TwoTerm low = twoSum(running, product.tail);
        appendNonZero(low.tail, h, hSize);
        // The paper proves |product.head| >= |low.head| here, so Fast-Two-Sum is exact.
        const TwoTerm high = fastTwoSum(product.head, low.head);
        appendNonZero(high.tail, h, hSize);
        running = high.head;
    }
    appendLast(running, h, hSize);
    return hSize;
}

/// Fast-Expansion-Sum (paper Theorem 13): h = e + f, at most eSize + fSize components. Merges
/// the two inputs by increasing magnitude and sweeps the merged sequence with Two-Sum. Needs
/// strongly nonoverlapping inputs and round-to-even; every routine here preserves that property.
std::size_t sumExpansions(const double* e, std::size_t eSize, const double* f, std::size_t fSize,
                          double* h) {
    std::size_t i = 0;
    std::size_t j = 0;
    auto nextSmallest = [&]() {
        if (j == fSize || (i < eSize && std::fabs(e[i]) < std::fabs(f[j]))) {
            return e[i++];
        }
        return f[j++];
    };
    std::size_t hSize = 0;
    double running = nextSmallest();
    if (i + j < eSize + fSize) {
        // The merge order guarantees |second| >= |running|.
        const TwoTerm sum = fastTwoSum(nextSmallest(), running);
        appendNonZero(sum.tail, h, hSize);
        running = sum.head;
    }
    while (i + j < eSize + fSize) {
        const TwoTerm sum = twoSum(running, nextSmallest());
        appendNonZero(sum.tail, h, hSize);
        running = sum.head;
    }
    appendLast(running, h, hSize);
    return hSize;
}

// Capacity-checked wrappers: the result type's capacity is the worst-case length.

Expansion<2> exactDifference(double a, double b) {
    const TwoTerm diff = twoDiff(a, b);
    Expansion<2> h;
    appendNonZero(diff.tail, h.terms.data(), h.size);
    appendLast(diff.head, h.terms.data(), h.size);
    return h;
}

Expansion<2> exactProduct(double a, double b) {
    const TwoTerm product = twoProduct(a, b);
    Expansion<2> h;
    appendNonZero(product.tail, h.terms.data(), h.size);
    appendLast(product.head, h.terms.data(), h.size);
    return h;
}

/// left - right for two-component expansions (the paper's Two-Two-Diff, as two grows).
Expansion<4> twoTwoDifference(const Expansion<2>& left, const Expansion<2>& right) {
    Expansion<4> h;
    std::array<double, 3> partial;
    const std::size_t partialSize =
        growExpansion(left.terms.data(), left.size, -right.terms[0], partial.data());
    if (right.size == 1) {
        std::copy_n(partial.begin(), partialSize, h.terms.begin());
        h.size = partialSize;
    } else {
        h.size = growExpansion(partial.data(), partialSize, -right.terms[1], h.terms.data());
    }
    return h;
}

template <std::size_t N> Expansion<2 * N> scale(const Expansion<N>& e, double b) {
    Expansion<2 * N> h;
    h.size = scaleExpansion(e.terms.data(), e.size, b, h.terms.data());
    return h;
}

template <std::size_t N, std::size_t M>
Expansion<N + M> sum(const Expansion<N>& e, const Expansion<M>& f) {
    Expansion<N + M> h;
    h.size = sumExpansions(e.terms.data(), e.size, f.terms.data(), f.size, h.terms.data());
    return h;
}

template <std::size_t N, std::size_t M>
Expansion<N + M> difference(const Expansion<N>& e, const Expansion<M>& f) {
    Expansion<M> negated;
    negated.size = f.size;
    for (std::size_t i = 0; i < f.size; ++i) {
        negated.terms[i] = -f.terms[i];
    }
    return sum(e, negated);
}

/// e * f as the sum of e scaled by each component of f (paper section 2.8).
template <std::size_t N, std::size_t M>
Expansion<2 * N * M> product(const Expansion<N>& e, const Expansion<M>& f) {
    Expansion<2 * N * M> result;
    Expansion<2 * N * M> scratch;
    Expansion<2 * N> partial;
    double* accumulated = result.terms.data();
    double* next = scratch.terms.data();
    std::size_t accumulatedSize = scaleExpansion(e.terms.data(), e.size, f.terms[0], accumulated);
    for (std::size_t j = 1; j < f.size; ++j) {
        partial.size = scaleExpansion(e.terms.data(), e.size, f.terms[j], partial.terms.data());
        accumulatedSize =
            sumExpansions(accumulated, accumulatedSize, partial.terms.data(), partial.size, next);
        std::swap(accumulated, next);
    }
    if (accumulated != result.terms.data()) {
        std::copy_n(accumulated, accumulatedSize, result.terms.data());
    }
    result.size = accumulatedSize;
    return result;
}

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

    // Stage C: the first-order change of sum(lift * minor) when each rounded difference gains
    // its tail: d(lift) * minor + lift * d(minor), with d(dx^2 + dy^2) = 2 (dx dxTail + dy dyTail).
    errorBound = kIncircleErrorBoundC * permanent + kResultErrorBound * std::fabs(det);
    det += ((adx * adx + ady * ady) *
                ((bdx * cdyTail + cdy * bdxTail) - (bdy * cdxTail + cdx * bdyTail)) +
            2.0 * (adx * adxTail + ady * adyTail) * (bdx * cdy - bdy * cdx)) +
           ((bdx * bdx + bdy * bdy) *
                ((cdx * adyTail + ady * cdxTail) - (cdy * adxTail + adx * cdyTail)) +
            2.0 * (bdx * bdxTail + bdy * bdyTail) * (cdx * ady - cdy * adx)) +
           ((cdx * cdx + cdy * cdy) *
                ((adx * bdyTail + bdy * adxTail) - (ady * bdxTail + bdx * adyTail)) +
            2.0 * (cdx * cdxTail + cdy * cdyTail) * (adx * bdy - ady * bdx));
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

#pragma once
/// @file
/// Exact floating-point expansion arithmetic for the adaptive predicates (predicates.cpp), after
/// J. R. Shewchuk, "Adaptive Precision Floating-Point Arithmetic and Fast Robust Geometric
/// Predicates", Discrete & Computational Geometry 18:305-363 (1997), section 2. Written from
/// the paper's algorithms, not copied from its predicates.c.
///
/// Notation. u = 2^-53 is the unit roundoff. An *expansion* is an unevaluated sum of doubles
/// e[0] + e[1] + ... + e[n-1], stored from smallest to largest magnitude, whose components do
/// not overlap (each one's lowest set bit lies above the highest set bit of the one before), so
/// its value is exact and its sign is the sign of its largest component. Every routine here
/// eliminates zero components, so the last component is the most significant one (an
/// expansion of value zero is the single component 0).
///
/// Needs IEEE-754 binary64 without excess precision and round-to-nearest-even, as predicates.cpp
/// checks; Fast-Expansion-Sum's proof needs the round-to-even tie break.
///
/// Included by predicates.cpp alone, whose adaptive stages are built from these: they have
/// internal linkage (an unnamed namespace), so that the compiler weighs inlining them into the
/// stages exactly as it did when they were written in that file. Declared inline instead,
/// the expansion loops were inlined into every stage (orient2dAdaptive twice its size): a
/// change to the hot predicates' code that moving them here was not meant to make.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>

namespace terratin::predicates::detail {
namespace {

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

} // namespace
} // namespace terratin::predicates::detail

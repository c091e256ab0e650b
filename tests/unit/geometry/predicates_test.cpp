#include "terratin/geometry/predicates.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <initializer_list>
#include <limits>
#include <numbers>
#include <random>
#include <stdexcept>
#include <vector>

// Every expected sign below comes from an exact reference: the double coordinates of a case are
// dyadic rationals m * 2^e, so after scaling by a common power of two they are integers, and
// the determinants are evaluated on those integers with a small arbitrary-precision integer
// type. No floating-point operation is involved in the reference, so it is exact by
// construction (and is itself checked against plain int64 arithmetic on small integers).

namespace terratin {
namespace {

using predicates::incircle;
using predicates::orient2d;

// ---------------------------------------------------------------------------------------------
// Exact reference arithmetic.

/// Signed arbitrary-precision integer: sign and magnitude, magnitude in base-2^32 limbs,
/// least significant first, without leading zero limbs (zero has no limbs and is non-negative).
class BigInt {
public:
    BigInt() = default;

    explicit BigInt(std::int64_t value) : m_negative(value < 0) {
        // Negate in unsigned arithmetic so that INT64_MIN is handled too.
        std::uint64_t magnitude = static_cast<std::uint64_t>(value);
        if (m_negative) {
            magnitude = ~magnitude + 1U;
        }
        while (magnitude != 0) {
            m_limbs.push_back(static_cast<std::uint32_t>(magnitude));
            magnitude >>= 32U;
        }
    }

    /// The integer value / 2^exponentBase; throws unless value is a multiple of 2^exponentBase.
    static BigInt fromScaledDouble(double value, int exponentBase) {
        if (value == 0.0) {
            return BigInt{};
        }
        int exponent = 0;
        const double fraction = std::frexp(value, &exponent); // value = fraction * 2^exponent
        // |fraction| is in [0.5, 1) with at most 53 significant bits, so this is an integer.
        const auto significand = static_cast<std::int64_t>(std::ldexp(fraction, 53));
        const int shift = exponent - 53 - exponentBase;
        if (shift < 0) {
            throw std::logic_error("exponentBase too large for this value");
        }
        BigInt result(significand);
        result.shiftLeft(shift);
        return result;
    }

    int sign() const { return m_limbs.empty() ? 0 : (m_negative ? -1 : 1); }

    friend BigInt operator+(const BigInt& a, const BigInt& b) {
        if (a.m_negative == b.m_negative) {
            return make(a.m_negative, addMagnitudes(a.m_limbs, b.m_limbs));
        }
        const int order = compareMagnitudes(a.m_limbs, b.m_limbs);
        if (order == 0) {
            return BigInt{};
        }
        return order > 0 ? make(a.m_negative, subtractMagnitudes(a.m_limbs, b.m_limbs))
                         : make(b.m_negative, subtractMagnitudes(b.m_limbs, a.m_limbs));
    }

    friend BigInt operator-(const BigInt& a, const BigInt& b) {
        BigInt negated = b;
        negated.m_negative = !negated.m_limbs.empty() && !b.m_negative;
        return a + negated;
    }

    friend BigInt operator*(const BigInt& a, const BigInt& b) {
        if (a.m_limbs.empty() || b.m_limbs.empty()) {
            return BigInt{};
        }
        std::vector<std::uint32_t> limbs(a.m_limbs.size() + b.m_limbs.size(), 0);
        for (std::size_t i = 0; i < a.m_limbs.size(); ++i) {
            std::uint64_t carry = 0;
            for (std::size_t j = 0; j < b.m_limbs.size(); ++j) {
                // (2^32 - 1)^2 + 2 (2^32 - 1) < 2^64: no overflow.
                const std::uint64_t t =
                    std::uint64_t{a.m_limbs[i]} * b.m_limbs[j] + limbs[i + j] + carry;
                limbs[i + j] = static_cast<std::uint32_t>(t);
                carry = t >> 32U;
            }
            limbs[i + b.m_limbs.size()] = static_cast<std::uint32_t>(carry);
        }
        return make(a.m_negative != b.m_negative, std::move(limbs));
    }

private:
    using Limbs = std::vector<std::uint32_t>;

    static BigInt make(bool negative, Limbs limbs) {
        BigInt result;
        result.m_limbs = std::move(limbs);
        while (!result.m_limbs.empty() && result.m_limbs.back() == 0) {
            result.m_limbs.pop_back();
        }
        result.m_negative = negative && !result.m_limbs.empty();
        return result;
    }

    void shiftLeft(int bits) {
        const auto limbShift = static_cast<std::size_t>(bits / 32);
        const auto bitShift = static_cast<unsigned>(bits % 32);
        Limbs shifted(limbShift, 0);
        std::uint32_t carry = 0;
        for (const std::uint32_t limb : m_limbs) {
            shifted.push_back(bitShift == 0 ? limb : (limb << bitShift) | carry);
            carry = bitShift == 0 ? 0 : limb >> (32U - bitShift);
        }
        shifted.push_back(carry);
        *this = make(m_negative, std::move(shifted));
    }

    static int compareMagnitudes(const Limbs& a, const Limbs& b) {
        if (a.size() != b.size()) {
            return a.size() < b.size() ? -1 : 1;
        }
        for (std::size_t i = a.size(); i-- > 0;) {
            if (a[i] != b[i]) {
                return a[i] < b[i] ? -1 : 1;
            }
        }
        return 0;
    }

    static Limbs addMagnitudes(const Limbs& a, const Limbs& b) {
        Limbs sum(std::max(a.size(), b.size()) + 1, 0);
        std::uint64_t carry = 0;
        for (std::size_t i = 0; i + 1 < sum.size(); ++i) {
            const std::uint64_t t = carry + (i < a.size() ? a[i] : 0U) + (i < b.size() ? b[i] : 0U);
            sum[i] = static_cast<std::uint32_t>(t);
            carry = t >> 32U;
        }
        sum.back() = static_cast<std::uint32_t>(carry);
        return sum;
    }

    /// larger - smaller for |larger| >= |smaller|.
    static Limbs subtractMagnitudes(const Limbs& larger, const Limbs& smaller) {
        Limbs difference(larger.size(), 0);
        std::int64_t borrow = 0;
        for (std::size_t i = 0; i < larger.size(); ++i) {
            std::int64_t t =
                std::int64_t{larger[i]} - (i < smaller.size() ? smaller[i] : 0) - borrow;
            borrow = t < 0 ? 1 : 0;
            if (t < 0) {
                t += std::int64_t{1} << 32;
            }
            difference[i] = static_cast<std::uint32_t>(t);
        }
        return difference;
    }

    bool m_negative = false;
    Limbs m_limbs;
};

/// The largest e such that every value is an integer multiple of 2^e.
int commonExponent(std::initializer_list<double> values) {
    int lowest = std::numeric_limits<int>::max();
    for (const double value : values) {
        if (value != 0.0) {
            int exponent = 0;
            std::frexp(value, &exponent);
            lowest = std::min(lowest, exponent - 53);
        }
    }
    return lowest == std::numeric_limits<int>::max() ? 0 : lowest;
}

int signOf(double value) {
    return (value > 0.0) - (value < 0.0);
}

int exactOrient2dSign(const Point2& a, const Point2& b, const Point2& c) {
    const int base = commonExponent({a.x, a.y, b.x, b.y, c.x, c.y});
    auto big = [base](double v) { return BigInt::fromScaledDouble(v, base); };
    const BigInt acx = big(a.x) - big(c.x);
    const BigInt bcx = big(b.x) - big(c.x);
    const BigInt acy = big(a.y) - big(c.y);
    const BigInt bcy = big(b.y) - big(c.y);
    return (acx * bcy - acy * bcx).sign();
}

int exactIncircleSign(const Point2& a, const Point2& b, const Point2& c, const Point2& d) {
    const int base = commonExponent({a.x, a.y, b.x, b.y, c.x, c.y, d.x, d.y});
    auto big = [base](double v) { return BigInt::fromScaledDouble(v, base); };
    const BigInt adx = big(a.x) - big(d.x);
    const BigInt bdx = big(b.x) - big(d.x);
    const BigInt cdx = big(c.x) - big(d.x);
    const BigInt ady = big(a.y) - big(d.y);
    const BigInt bdy = big(b.y) - big(d.y);
    const BigInt cdy = big(c.y) - big(d.y);
    const BigInt det = (adx * adx + ady * ady) * (bdx * cdy - cdx * bdy) +
                       (bdx * bdx + bdy * bdy) * (cdx * ady - adx * cdy) +
                       (cdx * cdx + cdy * cdy) * (adx * bdy - bdx * ady);
    return det.sign();
}

/// +1 for an even permutation of 0..n-1, -1 for an odd one.
template <std::size_t N> int parityOf(const std::array<int, N>& permutation) {
    int inversions = 0;
    for (std::size_t i = 0; i < N; ++i) {
        for (std::size_t j = i + 1; j < N; ++j) {
            inversions += permutation[i] > permutation[j] ? 1 : 0;
        }
    }
    return inversions % 2 == 0 ? 1 : -1;
}

/// value moved by `steps` representable doubles (negative steps move down).
double ulpsAway(double value, int steps) {
    const double direction = steps < 0 ? -std::numeric_limits<double>::infinity()
                                       : std::numeric_limits<double>::infinity();
    for (int i = 0; i < std::abs(steps); ++i) {
        value = std::nextafter(value, direction);
    }
    return value;
}

// Deterministic seed so that a failure reproduces.
constexpr std::uint64_t kSeed = 20240611;

/// A random double with a random exponent in [minExponent, maxExponent] and a full random
/// significand, of random sign.
double randomWideDouble(std::mt19937_64& rng, int minExponent, int maxExponent) {
    std::uniform_int_distribution<int> exponent(minExponent, maxExponent);
    std::uniform_real_distribution<double> fraction(0.5, 1.0);
    const double magnitude = std::ldexp(fraction(rng), exponent(rng));
    return (rng() & 1U) != 0 ? magnitude : -magnitude;
}

// ---------------------------------------------------------------------------------------------
// The reference itself.

TEST(Orient2dReference, MatchesInt64_WhenSmallIntegerCoordinates) {
    std::mt19937_64 rng(kSeed);
    std::uniform_int_distribution<std::int64_t> coordinate(-(1 << 20), 1 << 20);
    for (int trial = 0; trial < 2000; ++trial) {
        const std::int64_t ax = coordinate(rng), ay = coordinate(rng), bx = coordinate(rng),
                           by = coordinate(rng), cx = coordinate(rng), cy = coordinate(rng);
        // |terms| <= (2^21)^2 * 2: far inside int64.
        const std::int64_t det = (ax - cx) * (by - cy) - (ay - cy) * (bx - cx);
        const int expected = (det > 0) - (det < 0);
        ASSERT_EQ(exactOrient2dSign({static_cast<double>(ax), static_cast<double>(ay)},
                                    {static_cast<double>(bx), static_cast<double>(by)},
                                    {static_cast<double>(cx), static_cast<double>(cy)}),
                  expected);
    }
}

TEST(IncircleReference, MatchesInt64_WhenSmallIntegerCoordinates) {
    std::mt19937_64 rng(kSeed);
    // Small range so that many quadruples are exactly cocircular and all terms fit int64:
    // differences <= 2^11, lifts <= 2^23, minors <= 2^23, sum of three products < 2^48.
    std::uniform_int_distribution<std::int64_t> coordinate(-(1 << 10), 1 << 10);
    std::uniform_int_distribution<std::int64_t> tiny(-3, 3);
    for (int trial = 0; trial < 4000; ++trial) {
        auto& dist = trial % 2 == 0 ? coordinate : tiny;
        std::array<std::int64_t, 8> v{};
        for (auto& x : v) {
            x = dist(rng);
        }
        const std::int64_t adx = v[0] - v[6], ady = v[1] - v[7], bdx = v[2] - v[6],
                           bdy = v[3] - v[7], cdx = v[4] - v[6], cdy = v[5] - v[7];
        const std::int64_t det = (adx * adx + ady * ady) * (bdx * cdy - cdx * bdy) +
                                 (bdx * bdx + bdy * bdy) * (cdx * ady - adx * cdy) +
                                 (cdx * cdx + cdy * cdy) * (adx * bdy - bdx * ady);
        auto p = [&](std::size_t i) {
            return Point2{static_cast<double>(v[2 * i]), static_cast<double>(v[2 * i + 1])};
        };
        ASSERT_EQ(exactIncircleSign(p(0), p(1), p(2), p(3)), (det > 0) - (det < 0));
    }
}

// ---------------------------------------------------------------------------------------------
// orient2d

TEST(Orient2d, ReturnsPositive_WhenCounterClockwise) {
    EXPECT_GT(orient2d({0.0, 0.0}, {1.0, 0.0}, {0.0, 1.0}), 0.0);
    EXPECT_GT(orient2d({500000.0, 5000000.0}, {500010.0, 5000000.0}, {500000.0, 5000010.0}), 0.0);
}

TEST(Orient2d, ReturnsNegative_WhenClockwise) {
    EXPECT_LT(orient2d({0.0, 0.0}, {0.0, 1.0}, {1.0, 0.0}), 0.0);
}

TEST(Orient2d, ReturnsTwiceTheSignedArea_WhenWellConditioned) {
    EXPECT_EQ(orient2d({0.0, 0.0}, {4.0, 0.0}, {0.0, 3.0}), 12.0);
    EXPECT_EQ(orient2d({1.0, 1.0}, {1.0, 4.0}, {5.0, 1.0}), -12.0);
}

TEST(Orient2d, ReturnsZero_WhenCollinearOrCoincident) {
    EXPECT_EQ(orient2d({0.0, 0.0}, {1.0, 1.0}, {2.0, 2.0}), 0.0);
    EXPECT_EQ(orient2d({0.0, 5.0}, {1.0, 5.0}, {-7.0, 5.0}), 0.0); // a grid row
    EXPECT_EQ(orient2d({3.0, 4.0}, {3.0, 4.0}, {-1.0, 2.0}), 0.0); // a == b
    EXPECT_EQ(orient2d({3.0, 4.0}, {3.0, 4.0}, {3.0, 4.0}), 0.0);
}

// The classic example of Kettner, Mehlhorn, Pion, Schirra and Yap ("Classroom examples of
// robustness problems in geometric computations", 2008): a point perturbed on a 2^-53 grid
// around (0.5, 0.5), tested against the line through (12, 12) and (24, 24).
TEST(Orient2d, MatchesExactSign_WhenGridPerturbedNearLine) {
    constexpr int kGridSize = 256;
    const double step = std::ldexp(1.0, -53); // one ulp of 0.5
    const Point2 b{12.0, 12.0};
    const Point2 c{24.0, 24.0};
    int naiveWrong = 0;
    int zeros = 0;
    for (int i = 0; i < kGridSize; ++i) {
        for (int j = 0; j < kGridSize; ++j) {
            const Point2 a{0.5 + i * step, 0.5 + j * step};
            const int expected = exactOrient2dSign(a, b, c);
            ASSERT_EQ(signOf(orient2d(a, b, c)), expected) << "i=" << i << " j=" << j;
            ASSERT_EQ(signOf(orient2d(b, c, a)), expected) << "i=" << i << " j=" << j;
            ASSERT_EQ(signOf(orient2d(c, a, b)), expected) << "i=" << i << " j=" << j;
            // The textbook formula, anchored at the perturbed point as in the paper.
            const double naive = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
            naiveWrong += signOf(naive) != expected ? 1 : 0;
            zeros += expected == 0 ? 1 : 0;
        }
    }
    // The case is only a meaningful test if plain double evaluation gets it wrong.
    EXPECT_GT(naiveWrong, 1000);
    EXPECT_EQ(zeros, kGridSize); // exactly the diagonal i == j is collinear
}

TEST(Orient2d, ReturnsZero_WhenCollinearWithLargeOffset) {
    // (origin, spacing): the spacing is one ulp (or a few) of the offset, so the points are as
    // close as doubles allow; integer slopes keep every point representable.
    const std::array<std::array<double, 2>, 5> cases{{
        {1e6, std::ldexp(1.0, -33)},
        {-5e6, std::ldexp(1.0, -30)},
        {1e15, 0.125},
        {1e15, 0.375},
        {std::ldexp(1.0, 60), std::ldexp(1.0, 8)},
    }};
    for (const auto& frame : cases) {
        const double origin = frame[0];
        const double spacing = frame[1];
        for (const double slope : {1.0, -1.0, 2.0, -3.0, 4.0}) {
            auto at = [&](double k) {
                return Point2{origin + k * spacing, origin + slope * k * spacing};
            };
            const Point2 a = at(0.0), b = at(1.0), c = at(7.0), d = at(-4.0);
            EXPECT_EQ(orient2d(a, b, c), 0.0) << origin << " " << spacing << " " << slope;
            EXPECT_EQ(orient2d(d, c, a), 0.0) << origin << " " << spacing << " " << slope;
            EXPECT_EQ(orient2d(b, d, c), 0.0) << origin << " " << spacing << " " << slope;
        }
    }
}

TEST(Orient2d, ReturnsCorrectSign_WhenOneUlpOffCollinear) {
    for (const double origin : {0.0, 1.0, 1e6, -5e6, 1e15}) {
        const Point2 a{origin, origin};
        const Point2 c{origin + 8.0, origin + 8.0};
        const Point2 onLine{origin + 3.0, origin + 3.0};
        // Moving the middle point up one ulp puts it left of a -> c (counter-clockwise).
        const Point2 above{onLine.x, ulpsAway(onLine.y, 1)};
        const Point2 below{onLine.x, ulpsAway(onLine.y, -1)};
        EXPECT_EQ(orient2d(a, c, onLine), 0.0) << origin;
        EXPECT_GT(orient2d(a, c, above), 0.0) << origin;
        EXPECT_LT(orient2d(a, c, below), 0.0) << origin;
        EXPECT_LT(orient2d(c, a, above), 0.0) << origin;
    }
}

// Points p * 2^i on a line through the origin are exactly collinear whatever the direction p,
// but with exponents i far apart their differences are not representable: the filter and the
// first adaptive stages cannot decide, so this exercises the exact stage.
TEST(Orient2d, ReturnsZero_WhenCollinearWithInexactDifferences) {
    std::mt19937_64 rng(kSeed);
    std::uniform_int_distribution<int> exponent(-30, 30);
    for (int trial = 0; trial < 3000; ++trial) {
        const double px = randomWideDouble(rng, -10, 10);
        const double py = randomWideDouble(rng, -10, 10);
        auto onLine = [&]() {
            const int e = exponent(rng);
            return Point2{std::ldexp(px, e), std::ldexp(py, e)};
        };
        const Point2 a = onLine(), b = onLine(), c = onLine();
        ASSERT_EQ(orient2d(a, b, c), 0.0) << trial;
        ASSERT_EQ(orient2d(c, a, b), 0.0) << trial;
        // One ulp off the line must be decided exactly too.
        const Point2 bOff{b.x, ulpsAway(b.y, trial % 3 == 0 ? -1 : 1)};
        ASSERT_EQ(signOf(orient2d(a, bOff, c)), exactOrient2dSign(a, bOff, c)) << trial;
        ASSERT_EQ(signOf(orient2d(bOff, c, a)), exactOrient2dSign(a, bOff, c)) << trial;
    }
}

TEST(Orient2d, SignFollowsPermutationParity_WhenArgumentsPermuted) {
    std::mt19937_64 rng(kSeed);
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    for (int trial = 0; trial < 3000; ++trial) {
        // Nearly collinear triples around a UTM-like origin, a third of them exactly collinear.
        const Point2 a{500000.0 + unit(rng), 5000000.0 + unit(rng)};
        Point2 c{500000.0 + unit(rng), 5000000.0 + unit(rng)};
        const double t = unit(rng);
        Point2 b{a.x + t * (c.x - a.x), a.y + t * (c.y - a.y)};
        if (trial % 3 == 0) {
            // Steps on a 2^-20 lattice keep every point representable (the coordinates' ulp is
            // at most 2^-29), so these are exactly collinear.
            const double stepX = std::ldexp(std::round(1024.0 * unit(rng)), -20);
            const double stepY = std::ldexp(std::round(1024.0 * unit(rng)), -20);
            b = {a.x + 3.0 * stepX, a.y + 3.0 * stepY};
            c = {a.x - 5.0 * stepX, a.y - 5.0 * stepY};
        }
        const std::array<Point2, 3> points{a, b, c};
        const int reference = signOf(orient2d(a, b, c));
        ASSERT_EQ(reference, exactOrient2dSign(a, b, c));
        std::array<int, 3> permutation{0, 1, 2};
        do {
            const int expected = parityOf(permutation) * reference;
            ASSERT_EQ(signOf(orient2d(points[static_cast<std::size_t>(permutation[0])],
                                      points[static_cast<std::size_t>(permutation[1])],
                                      points[static_cast<std::size_t>(permutation[2])])),
                      expected);
        } while (std::next_permutation(permutation.begin(), permutation.end()));
    }
}

TEST(Orient2d, MatchesExactSign_WhenRandomNearlyCollinear) {
    std::mt19937_64 rng(kSeed);
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    std::uniform_int_distribution<int> ulps(-3, 3);
    int zeros = 0;
    for (const double origin : {0.0, 1.0, 1e6, -5e6, 1e15}) {
        for (const double spread : {1e-9, 1e-3, 1.0, 1e4}) {
            for (int trial = 0; trial < 1000; ++trial) {
                const Point2 a{origin + spread * unit(rng), origin + spread * unit(rng)};
                const Point2 c{origin + spread * unit(rng), -origin + spread * unit(rng)};
                const double t = 1.5 * unit(rng) + 0.5;
                const Point2 b{ulpsAway(a.x + t * (c.x - a.x), ulps(rng)),
                               ulpsAway(a.y + t * (c.y - a.y), ulps(rng))};
                const int expected = exactOrient2dSign(a, b, c);
                ASSERT_EQ(signOf(orient2d(a, b, c)), expected)
                    << origin << " " << spread << " " << trial;
                ASSERT_EQ(signOf(orient2d(b, c, a)), expected);
                ASSERT_EQ(signOf(orient2d(c, a, b)), expected);
                zeros += expected == 0 ? 1 : 0;
            }
        }
    }
    EXPECT_GT(zeros, 0); // some exact ties were generated and kept as ties
}

TEST(Orient2d, MatchesExactSign_WhenCoordinatesSpanManyMagnitudes) {
    std::mt19937_64 rng(kSeed);
    for (int trial = 0; trial < 20000; ++trial) {
        std::array<Point2, 3> p{};
        for (auto& point : p) {
            point = {randomWideDouble(rng, -60, 60), randomWideDouble(rng, -60, 60)};
        }
        if (trial % 2 == 0) {
            // Put the third point near the line of the first two, where cancellation is worst.
            const double t = std::ldexp(1.0, trial % 40 - 20);
            p[2] = {p[0].x + t * (p[1].x - p[0].x), p[0].y + t * (p[1].y - p[0].y)};
        }
        ASSERT_EQ(signOf(orient2d(p[0], p[1], p[2])), exactOrient2dSign(p[0], p[1], p[2])) << trial;
    }
}

TEST(Orient2d, ExactStageMatchesReference_WhenCalledDirectly) {
    std::mt19937_64 rng(kSeed);
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    for (int trial = 0; trial < 10000; ++trial) {
        Point2 a{}, b{}, c{};
        if (trial % 2 == 0) {
            a = {randomWideDouble(rng, -60, 60), randomWideDouble(rng, -60, 60)};
            b = {randomWideDouble(rng, -60, 60), randomWideDouble(rng, -60, 60)};
            c = {randomWideDouble(rng, -60, 60), randomWideDouble(rng, -60, 60)};
        } else {
            a = {1e6 + unit(rng), 1e6 + unit(rng)};
            c = {-1e6 + unit(rng), unit(rng)};
            const double t = unit(rng);
            b = {a.x + t * (c.x - a.x), a.y + t * (c.y - a.y)};
        }
        ASSERT_EQ(signOf(predicates::detail::orient2dExact(a, b, c)), exactOrient2dSign(a, b, c));
    }
}

// ---------------------------------------------------------------------------------------------
// incircle

TEST(Incircle, ReturnsPositive_WhenInsideCounterClockwiseCircle) {
    EXPECT_GT(incircle({0.0, 0.0}, {2.0, 0.0}, {0.0, 2.0}, {0.5, 0.5}), 0.0);
}

TEST(Incircle, ReturnsNegative_WhenOutsideCounterClockwiseCircle) {
    EXPECT_LT(incircle({0.0, 0.0}, {2.0, 0.0}, {0.0, 2.0}, {3.0, 3.0}), 0.0);
}

TEST(Incircle, ReturnsNegative_WhenInsideClockwiseCircle) {
    EXPECT_LT(incircle({0.0, 0.0}, {0.0, 2.0}, {2.0, 0.0}, {0.5, 0.5}), 0.0);
}

TEST(Incircle, ReturnsZero_WhenPointsCoincide) {
    EXPECT_EQ(incircle({0.0, 0.0}, {2.0, 0.0}, {0.0, 2.0}, {2.0, 0.0}), 0.0); // d == b
    EXPECT_EQ(incircle({0.0, 0.0}, {0.0, 0.0}, {0.0, 2.0}, {7.0, 1.0}), 0.0); // a == b
}

/// The 12 integer points of the circle x^2 + y^2 = 25.
constexpr std::array<std::array<double, 2>, 12> kRadius5Lattice{{
    {5, 0},
    {4, 3},
    {3, 4},
    {0, 5},
    {-3, 4},
    {-4, 3},
    {-5, 0},
    {-4, -3},
    {-3, -4},
    {0, -5},
    {3, -4},
    {4, -3},
}};

TEST(Incircle, ReturnsZero_WhenIntegerPointsCocircular) {
    EXPECT_EQ(incircle({3.0, 4.0}, {4.0, 3.0}, {-3.0, 4.0}, {5.0, 0.0}), 0.0);
    // Every ordered choice of four of the twelve lattice points.
    for (std::size_t i = 0; i < kRadius5Lattice.size(); ++i) {
        for (std::size_t j = 0; j < kRadius5Lattice.size(); ++j) {
            for (std::size_t k = 0; k < kRadius5Lattice.size(); ++k) {
                for (std::size_t l = 0; l < kRadius5Lattice.size(); ++l) {
                    auto p = [](std::size_t n) {
                        return Point2{kRadius5Lattice[n][0], kRadius5Lattice[n][1]};
                    };
                    ASSERT_EQ(incircle(p(i), p(j), p(k), p(l)), 0.0) << i << j << k << l;
                }
            }
        }
    }
}

/// (origin, unit) pairs for which origin + 5 * unit and every lattice offset are representable,
/// with the unit as small as the origin's ulp allows: the circle is as tiny as doubles allow.
constexpr std::array<std::array<double, 2>, 6> kCircleFrames{{
    {0.0, 1.0},
    {1e6, 0x1p-33},
    {-5e6, 0x1p-30},
    {500000.0, 1.0},
    {1e15, 0.125},
    {0x1p60, 0x1p8},
}};

TEST(Incircle, ReturnsZero_WhenCocircularWithLargeOffset) {
    for (const auto& frame : kCircleFrames) {
        const double origin = frame[0];
        const double unit = frame[1];
        auto p = [&](std::size_t n) {
            return Point2{origin + unit * kRadius5Lattice[n][0],
                          -origin + unit * kRadius5Lattice[n][1]};
        };
        for (std::size_t i = 0; i + 3 < kRadius5Lattice.size(); ++i) {
            EXPECT_EQ(incircle(p(i), p(i + 1), p(i + 2), p(i + 3)), 0.0) << origin;
            EXPECT_EQ(incircle(p(i + 3), p(0), p(i + 1), p(i + 2)), 0.0) << origin;
        }
    }
}

TEST(Incircle, ReturnsCorrectSign_WhenPointMovedOneUlp) {
    for (const auto& frame : kCircleFrames) {
        const double origin = frame[0];
        const double unit = frame[1];
        auto at = [&](double x, double y) { return Point2{origin + unit * x, origin + unit * y}; };
        // Counter-clockwise along the circle: (5, 0) -> (3, 4) -> (-3, 4).
        const Point2 a = at(5, 0), b = at(3, 4), c = at(-3, 4);
        const Point2 d = at(4, -3);
        EXPECT_EQ(incircle(a, b, c, d), 0.0) << origin;
        // (4, -3) moved one ulp right leaves the circle; one ulp left enters it.
        const Point2 outside{ulpsAway(d.x, 1), d.y};
        const Point2 inside{ulpsAway(d.x, -1), d.y};
        EXPECT_LT(incircle(a, b, c, outside), 0.0) << origin;
        EXPECT_GT(incircle(a, b, c, inside), 0.0) << origin;
        // The same with the moved point in another argument position (odd permutation).
        EXPECT_GT(incircle(a, b, outside, c), 0.0) << origin;
        EXPECT_LT(incircle(inside, b, c, a), 0.0) << origin;
    }
}

// The corners of any axis-aligned rectangle and of any isosceles trapezoid symmetric about the
// y axis are exactly cocircular, whatever their coordinates: with coordinates of wildly
// different magnitudes the differences are inexact and only the exact stage can return 0.
TEST(Incircle, ReturnsZero_WhenRectangleOrTrapezoidCornersHaveMixedMagnitudes) {
    std::mt19937_64 rng(kSeed);
    for (int trial = 0; trial < 3000; ++trial) {
        const double x0 = randomWideDouble(rng, -40, 40), x1 = randomWideDouble(rng, -40, 40);
        const double y0 = randomWideDouble(rng, -40, 40), y1 = randomWideDouble(rng, -40, 40);
        std::array<Point2, 4> p{};
        if (trial % 2 == 0) {
            p = {Point2{x0, y0}, Point2{x1, y0}, Point2{x1, y1}, Point2{x0, y1}};
        } else {
            p = {Point2{-x0, y0}, Point2{x0, y0}, Point2{x1, y1}, Point2{-x1, y1}};
        }
        ASSERT_EQ(incircle(p[0], p[1], p[2], p[3]), 0.0) << trial;
        ASSERT_EQ(incircle(p[2], p[0], p[3], p[1]), 0.0) << trial;
        // A one-ulp nudge of one corner is decided exactly.
        const Point2 nudged{ulpsAway(p[3].x, trial % 3 == 0 ? -1 : 1), p[3].y};
        ASSERT_EQ(signOf(incircle(p[0], p[1], p[2], nudged)),
                  exactIncircleSign(p[0], p[1], p[2], nudged))
            << trial;
    }
}

// The incircle analogue of the grid example: d perturbed on a 2^-53 grid around (0.5, 0.5),
// which lies on the circle through (24.5, 0.5), (12.5, 12.5), (12.5, -11.5).
// Raster cells: the four corners of an axis-parallel rectangle with inexact coordinates, in
// every order, are cocircular; moving one corner by one ulp in x or y breaks that.
TEST(Incircle, MatchesExactSign_ForRasterCellCornersInEveryOrder) {
    for (const double offset : {0.0, 0.1, 4.0e5, -7.3e6}) {
        const double x0 = offset + 0.1;
        const double x1 = offset + 0.3;
        const double y0 = -offset + 0.7;
        const double y1 = -offset + 1.1;
        std::array<Point2, 4> corners{{{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}}};
        for (int moved = -1; moved < 8; ++moved) {
            std::array<Point2, 4> p = corners;
            if (moved >= 0) {
                Point2& corner = p[static_cast<std::size_t>(moved / 2)];
                (moved % 2 == 0 ? corner.x : corner.y) =
                    ulpsAway(moved % 2 == 0 ? corner.x : corner.y, 1);
            }
            std::array<int, 4> order{0, 1, 2, 3};
            do {
                const Point2& a = p[static_cast<std::size_t>(order[0])];
                const Point2& b = p[static_cast<std::size_t>(order[1])];
                const Point2& c = p[static_cast<std::size_t>(order[2])];
                const Point2& d = p[static_cast<std::size_t>(order[3])];
                const int expected = exactIncircleSign(a, b, c, d);
                ASSERT_EQ(signOf(incircle(a, b, c, d)), expected) << offset << " " << moved;
                if (moved < 0) {
                    ASSERT_EQ(expected, 0);
                }
            } while (std::next_permutation(order.begin(), order.end()));
        }
    }
}

TEST(Incircle, MatchesExactSign_WhenGridPerturbedNearCircle) {
    constexpr int kGridSize = 64;
    const double step = std::ldexp(1.0, -53);
    const Point2 a{24.5, 0.5}, b{12.5, 12.5}, c{12.5, -11.5};
    int naiveWrong = 0;
    for (int i = 0; i < kGridSize; ++i) {
        for (int j = 0; j < kGridSize; ++j) {
            const Point2 d{0.5 + i * step, 0.5 + j * step};
            const int expected = exactIncircleSign(a, b, c, d);
            ASSERT_EQ(signOf(incircle(a, b, c, d)), expected) << i << " " << j;
            ASSERT_EQ(signOf(incircle(d, a, b, c)), -expected) << i << " " << j;
            ASSERT_EQ(signOf(incircle(b, d, c, a)), expected) << i << " " << j;
            // Without the filter's guarantee: the same formula, no error bound.
            const double adx = a.x - d.x, ady = a.y - d.y, bdx = b.x - d.x, bdy = b.y - d.y,
                         cdx = c.x - d.x, cdy = c.y - d.y;
            const double naive = (adx * adx + ady * ady) * (bdx * cdy - cdx * bdy) +
                                 (bdx * bdx + bdy * bdy) * (cdx * ady - adx * cdy) +
                                 (cdx * cdx + cdy * cdy) * (adx * bdy - bdx * ady);
            naiveWrong += signOf(naive) != expected ? 1 : 0;
        }
    }
    EXPECT_GT(naiveWrong, 100); // about a third of the grid with plain doubles
}

TEST(Incircle, SignFollowsPermutationParity_WhenArgumentsPermuted) {
    std::mt19937_64 rng(kSeed);
    std::uniform_real_distribution<double> angle(0.0, 2.0 * std::numbers::pi);
    std::uniform_int_distribution<int> ulps(-2, 2);
    for (int trial = 0; trial < 1000; ++trial) {
        // Four points rounded onto a circle: nearly (or exactly) cocircular.
        const double cx = 500000.0, cy = 5000000.0, r = 10.0;
        std::array<Point2, 4> points{};
        for (auto& p : points) {
            const double theta = angle(rng);
            p = {ulpsAway(cx + r * std::cos(theta), ulps(rng)), cy + r * std::sin(theta)};
        }
        const int reference = signOf(incircle(points[0], points[1], points[2], points[3]));
        ASSERT_EQ(reference, exactIncircleSign(points[0], points[1], points[2], points[3]));
        std::array<int, 4> permutation{0, 1, 2, 3};
        do {
            auto p = [&](std::size_t i) {
                return points[static_cast<std::size_t>(permutation[i])];
            };
            ASSERT_EQ(signOf(incircle(p(0), p(1), p(2), p(3))), parityOf(permutation) * reference);
        } while (std::next_permutation(permutation.begin(), permutation.end()));
        // Rotating a, b, c is an even permutation: the sign is kept.
        EXPECT_EQ(signOf(incircle(points[1], points[2], points[0], points[3])), reference);
    }
}

TEST(Incircle, MatchesExactSign_WhenRandomNearlyCocircular) {
    std::mt19937_64 rng(kSeed);
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    std::uniform_real_distribution<double> angle(0.0, 2.0 * std::numbers::pi);
    std::uniform_int_distribution<int> ulps(-2, 2);
    for (const double origin : {0.0, 1.0, 1e6, -5e6, 1e12}) {
        for (const double radius : {1e-6, 1.0, 1e3, 1e6}) {
            for (int trial = 0; trial < 400; ++trial) {
                const Point2 centre{origin + radius * unit(rng), -origin + radius * unit(rng)};
                std::array<Point2, 4> p{};
                for (auto& point : p) {
                    const double theta = angle(rng);
                    point = {ulpsAway(centre.x + radius * std::cos(theta), ulps(rng)),
                             centre.y + radius * std::sin(theta)};
                }
                const int expected = exactIncircleSign(p[0], p[1], p[2], p[3]);
                ASSERT_EQ(signOf(incircle(p[0], p[1], p[2], p[3])), expected)
                    << origin << " " << radius << " " << trial;
                ASSERT_EQ(signOf(incircle(p[3], p[0], p[1], p[2])), -expected);
            }
        }
    }
}

// The one-sided filter: never true unless the exact sign is positive, and true for every
// point clearly inside; near-cocircular points it cannot decide count as outside.
TEST(IncircleSurelyInside, ImpliesExactInside_AndDecidesClearCases) {
    std::mt19937_64 rng(kSeed);
    std::uniform_real_distribution<double> angle(0.0, 2.0 * std::numbers::pi);
    std::uniform_int_distribution<int> ulps(-2, 2);
    int undecidedInside = 0;
    for (int trial = 0; trial < 4000; ++trial) {
        std::array<Point2, 4> p{};
        for (auto& point : p) {
            const double theta = angle(rng);
            point = {ulpsAway(1e3 + 50.0 * std::cos(theta), ulps(rng)),
                     -2e3 + 50.0 * std::sin(theta)};
        }
        if (exactOrient2dSign(p[0], p[1], p[2]) < 0)
            std::swap(p[0], p[1]);
        const int exact = exactIncircleSign(p[0], p[1], p[2], p[3]);
        const bool surely = predicates::incircleSurelyInside(p[0], p[1], p[2], p[3]);
        ASSERT_TRUE(!surely || exact > 0) << trial;
        undecidedInside += exact > 0 && !surely;
    }
    // Two ulps off one circle: stage A cannot tell these apart, so some inside points are
    // left undecided (that is the point of the filter).
    EXPECT_GT(undecidedInside, 0);

    const Point2 a{0.0, 0.0};
    const Point2 b{1.0, 0.0};
    const Point2 c{0.0, 1.0};
    EXPECT_TRUE(predicates::incircleSurelyInside(a, b, c, {0.5, 0.5}));
    EXPECT_FALSE(predicates::incircleSurelyInside(a, b, c, {2.0, 2.0}));
    EXPECT_FALSE(predicates::incircleSurelyInside(a, b, c, {1.0, 1.0})); // cocircular
    EXPECT_FALSE(predicates::incircleSurelyInside(a, b, c, a));          // a corner
    EXPECT_FALSE(predicates::incircleSurelyInside(b, a, c, {0.5, 0.5})); // clockwise
}

TEST(Incircle, MatchesExactSign_WhenCoordinatesSpanManyMagnitudes) {
    std::mt19937_64 rng(kSeed);
    for (int trial = 0; trial < 10000; ++trial) {
        std::array<Point2, 4> p{};
        for (auto& point : p) {
            point = {randomWideDouble(rng, -40, 40), randomWideDouble(rng, -40, 40)};
        }
        ASSERT_EQ(signOf(incircle(p[0], p[1], p[2], p[3])),
                  exactIncircleSign(p[0], p[1], p[2], p[3]))
            << trial;
    }
}

TEST(Incircle, ExactStageMatchesReference_WhenCalledDirectly) {
    std::mt19937_64 rng(kSeed);
    std::uniform_real_distribution<double> angle(0.0, 2.0 * std::numbers::pi);
    for (int trial = 0; trial < 4000; ++trial) {
        std::array<Point2, 4> p{};
        if (trial % 2 == 0) {
            for (auto& point : p) {
                point = {randomWideDouble(rng, -40, 40), randomWideDouble(rng, -40, 40)};
            }
        } else {
            for (auto& point : p) {
                const double theta = angle(rng);
                point = {0.25 + 1e6 * std::cos(theta), -3.0 + 1e6 * std::sin(theta)};
            }
        }
        ASSERT_EQ(signOf(predicates::detail::incircleExact(p[0], p[1], p[2], p[3])),
                  exactIncircleSign(p[0], p[1], p[2], p[3]))
            << trial;
    }
}

// ---------------------------------------------------------------------------------------------
// incircleTieBroken: cocircular points decided by a symbolic perturbation.

Point2 latticePoint(std::size_t n) {
    return {kRadius5Lattice[n][0], kRadius5Lattice[n][1]};
}

TEST(IncircleTieBroken, NeverZero_AndFollowsPermutationParity_OnCocircularPoints) {
    // Every choice of four distinct points of the radius-5 lattice, in every order.
    const std::size_t n = kRadius5Lattice.size();
    for (std::size_t i = 0; i < n; ++i)
        for (std::size_t j = i + 1; j < n; ++j)
            for (std::size_t k = j + 1; k < n; ++k)
                for (std::size_t l = k + 1; l < n; ++l) {
                    const std::array<Point2, 4> points{latticePoint(i), latticePoint(j),
                                                       latticePoint(k), latticePoint(l)};
                    const int reference =
                        predicates::incircleTieBroken(points[0], points[1], points[2], points[3]);
                    ASSERT_NE(reference, 0) << i << j << k << l;
                    std::array<int, 4> permutation{0, 1, 2, 3};
                    do {
                        auto p = [&](std::size_t m) {
                            return points[static_cast<std::size_t>(permutation[m])];
                        };
                        ASSERT_EQ(predicates::incircleTieBroken(p(0), p(1), p(2), p(3)),
                                  parityOf(permutation) * reference);
                    } while (std::next_permutation(permutation.begin(), permutation.end()));
                }
}

TEST(IncircleTieBroken, LeavesExactlyOneLegalDiagonal_InEveryCocircularQuadrilateral) {
    // The lattice is listed in no particular order: sort by angle for convex quadrilaterals.
    std::vector<Point2> ring;
    for (std::size_t i = 0; i < kRadius5Lattice.size(); ++i)
        ring.push_back(latticePoint(i));
    std::sort(ring.begin(), ring.end(), [](const Point2& a, const Point2& b) {
        return std::atan2(a.y, a.x) < std::atan2(b.y, b.x);
    });
    for (std::size_t i = 0; i < ring.size(); ++i)
        for (std::size_t j = i + 1; j < ring.size(); ++j)
            for (std::size_t k = j + 1; k < ring.size(); ++k)
                for (std::size_t l = k + 1; l < ring.size(); ++l) {
                    const Point2 &a = ring[i], &b = ring[j], &c = ring[k], &d = ring[l];
                    // Diagonal ac between (a, b, c) and (a, c, d); bd between (b, c, d) and
                    // (b, d, a). Legal: the opposite corner outside, seen from either side.
                    const bool acLegal = predicates::incircleTieBroken(a, b, c, d) < 0 &&
                                         predicates::incircleTieBroken(c, d, a, b) < 0;
                    const bool bdLegal = predicates::incircleTieBroken(b, c, d, a) < 0 &&
                                         predicates::incircleTieBroken(d, a, b, c) < 0;
                    EXPECT_NE(acLegal, bdLegal) << i << j << k << l;
                }
}

TEST(IncircleTieBroken, GivesEveryGridCellTheDiagonalAwayFromItsLargestCorner) {
    // The largest corner in (x, y) order is the top right one: every cell of a grid, at any
    // offset, is split by the same diagonal, from its top left to its bottom right corner.
    for (const auto& frame : kCircleFrames) {
        const double origin = frame[0];
        const double unit = frame[1];
        const Point2 bottomLeft{origin, origin};
        const Point2 bottomRight{origin + unit, origin};
        const Point2 topRight{origin + unit, origin + unit};
        const Point2 topLeft{origin, origin + unit};
        ASSERT_EQ(incircle(bottomLeft, bottomRight, topRight, topLeft), 0.0);
        // Diagonal bottom right - top left: topRight stays outside (bottomLeft, bottomRight,
        // topLeft)'s circle.
        EXPECT_LT(predicates::incircleTieBroken(bottomLeft, bottomRight, topLeft, topRight), 0);
        EXPECT_GT(predicates::incircleTieBroken(bottomLeft, bottomRight, topRight, topLeft), 0);
    }
}

TEST(IncircleTieBroken, AgreesWithIncircle_WhenNotCocircular) {
    std::mt19937_64 rng(kSeed);
    std::uniform_real_distribution<double> angle(0.0, 2.0 * std::numbers::pi);
    std::uniform_int_distribution<int> ulps(-2, 2);
    for (int trial = 0; trial < 1000; ++trial) {
        std::array<Point2, 4> points{};
        for (auto& p : points) {
            const double theta = angle(rng);
            p = {ulpsAway(500000.0 + 10.0 * std::cos(theta), ulps(rng)),
                 5000000.0 + 10.0 * std::sin(theta)};
        }
        const double det = incircle(points[0], points[1], points[2], points[3]);
        if (det != 0.0) {
            ASSERT_EQ(predicates::incircleTieBroken(points[0], points[1], points[2], points[3]),
                      signOf(det));
        }
    }
}

TEST(IncircleTieBroken, ReturnsZero_WhenAPointRepeats) {
    EXPECT_EQ(predicates::incircleTieBroken({0.0, 0.0}, {1.0, 0.0}, {0.0, 1.0}, {1.0, 0.0}), 0);
}

} // namespace
} // namespace terratin

#pragma once
/// @file
/// incircle on a lattice: when the eight coordinates of the four points are all small integer
/// multiples of one power of two, the determinant is computed exactly in 128-bit integers, far
/// sooner than by the expansions of the adaptive stages (predicates.cpp). A DEM's cell centres
/// are such points, in the triangulator's local frame as in map coordinates, and the exactly
/// cocircular ones among them (four centres on one circle) reach the adaptive stages on every
/// test. Internal to the predicates.

#include "terratin/geometry/point.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <optional>

namespace terratin::predicates::detail {

__extension__ using LatticeInt128 = __int128;

/// The largest magnitude, in bits, of a coordinate on the lattice. Differences then stay below
/// 2^30, each lift and each 2 x 2 minor below 2^61 (64-bit integers), each lifted term below
/// 2^122 and their sum below 2^124 (128-bit integers): nothing overflows.
inline constexpr int kLatticeBits = 29;

/// A nonzero finite double as odd * 2^exponent (odd: the significand without its trailing
/// zeros, signed, `width` bits long); nullopt for a subnormal, an infinity or a NaN.
struct OddTimesPowerOfTwo {
    std::int64_t odd = 0;
    int exponent = 0;
    int width = 0;
};
inline std::optional<OddTimesPowerOfTwo> splitDouble(double value) {
    const auto bits = std::bit_cast<std::uint64_t>(value);
    const auto biased = static_cast<int>((bits >> 52U) & 0x7ffU);
    if (biased == 0 || biased == 0x7ff)
        return std::nullopt;
    const std::uint64_t significand =
        (bits & ((std::uint64_t{1} << 52U) - 1U)) | (std::uint64_t{1} << 52U);
    const int zeros = std::countr_zero(significand);
    const auto odd = static_cast<std::int64_t>(significand >> static_cast<unsigned>(zeros));
    return OddTimesPowerOfTwo{(bits >> 63U) != 0 ? -odd : odd, biased - 1075 + zeros, 53 - zeros};
}

/// The coordinates (a.x, a.y, ..., d.y) as integers times one power of two, each below
/// 2^kLatticeBits in magnitude; nullopt when they are not.
inline std::optional<std::array<std::int64_t, 8>> onLattice(const std::array<double, 8>& values) {
    std::array<OddTimesPowerOfTwo, 8> parts{};
    int unit = 0;
    bool any = false;
    for (std::size_t i = 0; i < values.size(); ++i) {
        if (values[i] == 0.0)
            continue;
        const std::optional<OddTimesPowerOfTwo> part = splitDouble(values[i]);
        // A point measured rather than gridded uses its whole significand: no lattice.
        if (!part || part->width > kLatticeBits)
            return std::nullopt;
        parts[i] = *part;
        unit = any ? std::min(unit, part->exponent) : part->exponent;
        any = true;
    }
    std::array<std::int64_t, 8> integers{};
    for (std::size_t i = 0; i < values.size(); ++i) {
        if (parts[i].odd == 0)
            continue;
        const int shift = parts[i].exponent - unit;
        if (parts[i].width + shift > kLatticeBits)
            return std::nullopt;
        integers[i] = parts[i].odd * (std::int64_t{1} << static_cast<unsigned>(shift));
    }
    return integers;
}

/// The sign of incircle(a, b, c, d) (+1, -1 or 0, as a double) when the points lie on a lattice
/// (onLattice), else nullopt.
inline std::optional<double> latticeIncircle(const Point2& a, const Point2& b, const Point2& c,
                                             const Point2& d) {
    const std::optional<std::array<std::int64_t, 8>> lattice =
        onLattice({a.x, a.y, b.x, b.y, c.x, c.y, d.x, d.y});
    if (!lattice)
        return std::nullopt;
    const std::array<std::int64_t, 8>& v = *lattice;
    const std::int64_t adx = v[0] - v[6];
    const std::int64_t ady = v[1] - v[7];
    const std::int64_t bdx = v[2] - v[6];
    const std::int64_t bdy = v[3] - v[7];
    const std::int64_t cdx = v[4] - v[6];
    const std::int64_t cdy = v[5] - v[7];
    const auto lifted = [](std::int64_t lift, std::int64_t minor) {
        return static_cast<LatticeInt128>(lift) * minor;
    };
    const LatticeInt128 det = lifted(adx * adx + ady * ady, bdx * cdy - cdx * bdy) +
                              lifted(bdx * bdx + bdy * bdy, cdx * ady - adx * cdy) +
                              lifted(cdx * cdx + cdy * cdy, adx * bdy - bdx * ady);
    return det > 0 ? 1.0 : (det < 0 ? -1.0 : 0.0);
}

} // namespace terratin::predicates::detail

#pragma once
/// @file
/// incircle on a lattice: when the six coordinate differences of the four points (b - d and the
/// like) are exact and all small integer multiples of one power of two, the determinant is
/// computed exactly in integers, far sooner than by the expansions of the adaptive stages
/// (predicates.cpp). A DEM's cell centres are such points wherever the grid's origin lies (the
/// centres x0 + (i + 1/2) dx of a binade differ by exact multiples of dx when dx is a whole or
/// binary-fraction map unit), and the exactly cocircular ones among them (four centres on one
/// circle) reach the adaptive stages on every test. Internal to the predicates.

#include <algorithm>
#include <array>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <optional>

namespace terratin::predicates::detail {

__extension__ using LatticeInt128 = __int128;

/// The largest magnitude, in bits, of a difference on the lattice: each lift and each 2 x 2
/// minor then stays below 2^61 (64-bit integers), each lifted term below 2^122 and their sum
/// below 2^124 (128-bit integers): nothing overflows.
inline constexpr int kLatticeBits = 30;

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

/// The values as integers times one power of two, each below 2^kLatticeBits in magnitude;
/// nullopt when they are not.
inline std::optional<std::array<std::int64_t, 6>> onLattice(const std::array<double, 6>& values) {
    std::array<OddTimesPowerOfTwo, 6> parts{};
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
    std::array<std::int64_t, 6> integers{};
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

/// The sign of incircle (+1, -1 or 0, as a double) from the exact differences adx = a.x - d.x,
/// ady, bdx, bdy, cdx and cdy when they lie on a lattice (onLattice), else nullopt. The caller
/// checks that the differences are exact.
inline std::optional<double> latticeIncircle(double adx, double ady, double bdx, double bdy,
                                             double cdx, double cdy) {
    const std::optional<std::array<std::int64_t, 6>> lattice =
        onLattice({adx, ady, bdx, bdy, cdx, cdy});
    if (!lattice)
        return std::nullopt;
    const auto [ax, ay, bx, by, cx, cy] = *lattice;
    const auto lifted = [](std::int64_t lift, std::int64_t minor) {
        return static_cast<LatticeInt128>(lift) * minor;
    };
    const LatticeInt128 det = lifted(ax * ax + ay * ay, bx * cy - cx * by) +
                              lifted(bx * bx + by * by, cx * ay - ax * cy) +
                              lifted(cx * cx + cy * cy, ax * by - bx * ay);
    return det > 0 ? 1.0 : (det < 0 ? -1.0 : 0.0);
}

} // namespace terratin::predicates::detail

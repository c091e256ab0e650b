#pragma once
/// @file
/// Seeded insertion orders, identical on every platform (std::shuffle and the standard
/// distributions are implementation-defined, so they are not used).

#include "../huge_pages.hpp"
#include "terratin/geometry/point.hpp"

#include <cstdint>
#include <span>
#include <vector>

namespace terratin::detail {

/// A uniformly random permutation of the ids 0..count-1 except `skip`, drawn with
/// splitmix64 and Lemire's unbiased bounded integers.
HugePageArray<std::uint32_t> randomInsertionOrder(std::uint32_t count, std::uint32_t skip,
                                                  std::uint64_t seed);

/// A biased randomized insertion order (Amenta, Choi & Rote, "Incremental constructions con
/// BRIO", SoCG 2003) of the ids of `points` except `skip`: each point falls in round k with
/// probability 2^-(k+1), the rounds are inserted from the sparsest (highest k) to the densest
/// (k = 0, about half the points), and each round is sorted along a Hilbert curve. The
/// random rounds keep the expected O(n log n) bound of randomized insertion; the spatial sort
/// makes consecutive insertions walk almost the same DAG path, so memory access is local.
/// When `roundStarts` is given it receives the index in the order where each round begins.
/// The sort keys are computed with up to `threads` threads; the order does not depend on it.
HugePageArray<std::uint32_t> brioInsertionOrder(std::span<const Point2> points, std::uint32_t skip,
                                                std::uint64_t seed,
                                                std::vector<std::size_t>* roundStarts = nullptr,
                                                unsigned threads = 1);

} // namespace terratin::detail

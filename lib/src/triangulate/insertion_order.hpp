#pragma once
/// @file
/// Seeded random insertion orders, identical on every platform (std::shuffle and the standard
/// distributions are implementation-defined, so they are not used).

#include <cstdint>
#include <vector>

namespace terratin::detail {

/// A uniformly random permutation of the ids 0..count-1 except `skip`, drawn with
/// splitmix64 and Lemire's unbiased bounded integers.
std::vector<std::uint32_t> randomInsertionOrder(std::uint32_t count, std::uint32_t skip,
                                                std::uint64_t seed);

} // namespace terratin::detail

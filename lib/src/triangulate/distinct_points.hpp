#pragma once
/// @file
/// Exact duplicate detection for the triangulator's input: which points share their (x, y)
/// with an earlier point.

#include "../huge_pages.hpp"
#include "terratin/geometry/point.hpp"

#include <cstdint>
#include <span>
#include <vector>

namespace terratin::detail {

/// A point that repeats the (x, y) of an earlier one.
struct DuplicatePoint {
    /// Its input index.
    std::uint32_t index;
    /// The input index of the first point with the same (x, y).
    std::uint32_t first;
};

struct DistinctPoints {
    /// Input index of the first occurrence of every distinct (x, y), ascending.
    HugePageArray<std::uint32_t> firstOccurrences;
    /// Every other point, by ascending index.
    std::vector<DuplicatePoint> duplicates;
};

/// Finds the distinct (x, y) of `points` (-0 equals +0) by hashing, on up to `threads`
/// threads: O(n) expected, where sorting would cost O(n log n). The result does not depend on
/// the thread count.
DistinctPoints findDistinctPoints(std::span<const Point3> points, unsigned threads);

} // namespace terratin::detail

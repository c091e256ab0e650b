#pragma once
// Point sets for tests: the paper's distributions (the same generator terratin-bench uses)
// and the degenerate cases on top of them.

#include "distributions.hpp"
#include "terratin/geometry/point.hpp"

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace terratin::test {

using bench::Distribution;
using bench::generatePoints;

inline std::string toString(Distribution distribution) {
    return std::string(bench::toString(distribution));
}

/// `points` followed by `copies` exact copies of randomly chosen points with other z values.
std::vector<Point3> withDuplicates(std::vector<Point3> points, std::size_t copies,
                                   std::uint64_t seed);

/// `count` exactly collinear points on the line y = x / 2 + 1/4 plus one point off the line.
std::vector<Point3> collinearPlusOne(std::size_t count);

/// All integer points on the concentric circles x^2 + y^2 = r^2 for r in {5, 25, 65, 325,
/// 1105} (exactly cocircular sets), scaled by `scale` (a power of two keeps them exact).
std::vector<Point3> cocircularRings(double scale);

/// `points` moved by (dx, dy).
std::vector<Point3> offset(std::vector<Point3> points, double dx, double dy);

} // namespace terratin::test

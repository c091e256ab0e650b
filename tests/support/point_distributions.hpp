#pragma once
// Point sets for tests: the distributions of Kohout & Kolingerova's experiments (uniform,
// gauss, cluster, grid, arc in the unit square) and the degenerate cases on top of them.

#include "terratin/geometry/point.hpp"

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace terratin::test {

enum class Distribution { Uniform, Gauss, Cluster, Grid, Arc };

std::string toString(Distribution distribution);

/// About `count` points of `distribution` in the unit square (Grid rounds to a full square
/// grid; Arc puts the points on half a circle, the in-circle worst case). z is a smooth
/// function of (x, y).
std::vector<Point3> generatePoints(Distribution distribution, std::size_t count,
                                   std::uint64_t seed);

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

#pragma once
// The point distributions of Kohout & Kolingerova's experiments, in the unit square, shared
// by terratin-bench and the test suite (target terratin_point_distributions).

#include "terratin/geometry/point.hpp"

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string_view>
#include <vector>

namespace terratin::bench {

enum class Distribution {
    /// x and y uniform in [0, 1].
    Uniform,
    /// x and y normal with mean 0.5 and standard deviation 0.1; points outside the unit square
    /// are drawn again.
    Gauss,
    /// 10 uniform centres, each point normal around one of them with standard deviation 0.01;
    /// points outside the unit square are drawn again.
    Cluster,
    /// A side x side regular grid with spacing 1 / side, side = round(sqrt(count)): every
    /// cell's four corners are cocircular, so ties are everywhere.
    Grid,
    /// Uniform angles on the half circle of centre (0.5, 0) and radius 0.5: all points are on
    /// the convex hull and (up to the rounding of sin and cos) cocircular.
    Arc,
};

/// Every distribution, in the order the tables list them.
inline constexpr Distribution kAllDistributions[] = {Distribution::Uniform, Distribution::Gauss,
                                                     Distribution::Cluster, Distribution::Grid,
                                                     Distribution::Arc};

/// "uniform", "gauss", "cluster", "grid" or "arc".
std::string_view toString(Distribution distribution);

/// The distribution named `name` (as toString writes it), or nothing.
std::optional<Distribution> parseDistribution(std::string_view name);

/// About `count` points of `distribution` (exactly `count` except for Grid, which has
/// round(sqrt(count))^2), z a smooth function of x and y. The same seed gives the same points.
std::vector<Point3> generatePoints(Distribution distribution, std::size_t count,
                                   std::uint64_t seed);

} // namespace terratin::bench

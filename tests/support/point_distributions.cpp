#include "point_distributions.hpp"

#include <cmath>
#include <random>

namespace terratin::test {

std::vector<Point3> withDuplicates(std::vector<Point3> points, std::size_t copies,
                                   std::uint64_t seed) {
    std::mt19937_64 random(seed);
    std::uniform_int_distribution<std::size_t> pick(0, points.size() - 1);
    const std::size_t original = points.size();
    for (std::size_t i = 0; i < copies; ++i) {
        Point3 copy = points[pick(random) % original];
        copy.z += 1000.0 + static_cast<double>(i);
        points.push_back(copy);
    }
    return points;
}

std::vector<Point3> collinearPlusOne(std::size_t count) {
    std::vector<Point3> points;
    for (std::size_t i = 0; i < count; ++i) {
        // x is a multiple of 1/1024, so y = x / 2 + 1/4 is computed exactly: the points are
        // exactly collinear, not just up to rounding.
        const double x = static_cast<double>(i) / 1024.0;
        points.push_back({x, x / 2.0 + 0.25, static_cast<double>(i)});
    }
    points.push_back({0.5, -1.0, 7.0});
    return points;
}

std::vector<Point3> cocircularRings(double scale) {
    std::vector<Point3> points;
    for (const long radius : {5L, 25L, 65L, 325L, 1105L}) {
        for (long x = -radius; x <= radius; ++x) {
            const long ySquared = radius * radius - x * x;
            const auto y =
                static_cast<long>(std::llround(std::sqrt(static_cast<double>(ySquared))));
            if (y * y != ySquared)
                continue;
            points.push_back({static_cast<double>(x) * scale, static_cast<double>(y) * scale,
                              static_cast<double>(radius)});
            if (y != 0)
                points.push_back({static_cast<double>(x) * scale, static_cast<double>(-y) * scale,
                                  static_cast<double>(radius)});
        }
    }
    return points;
}

std::vector<Point3> offset(std::vector<Point3> points, double dx, double dy) {
    for (Point3& p : points) {
        p.x += dx;
        p.y += dy;
    }
    return points;
}

} // namespace terratin::test

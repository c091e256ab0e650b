#include "point_distributions.hpp"

#include <cmath>
#include <numbers>
#include <random>

namespace terratin::test {

namespace {
double terrainHeight(double x, double y) { return 100.0 * std::sin(3.0 * x) * std::cos(2.0 * y); }

Point3 withHeight(double x, double y) { return {x, y, terrainHeight(x, y)}; }
} // namespace

std::string toString(Distribution distribution) {
    switch (distribution) {
    case Distribution::Uniform:
        return "uniform";
    case Distribution::Gauss:
        return "gauss";
    case Distribution::Cluster:
        return "cluster";
    case Distribution::Grid:
        return "grid";
    case Distribution::Arc:
        return "arc";
    }
    return "unknown";
}

std::vector<Point3> generatePoints(Distribution distribution, std::size_t count,
                                   std::uint64_t seed) {
    std::mt19937_64 random(seed);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    std::vector<Point3> points;
    points.reserve(count);
    switch (distribution) {
    case Distribution::Uniform:
        for (std::size_t i = 0; i < count; ++i)
            points.push_back(withHeight(unit(random), unit(random)));
        break;
    case Distribution::Gauss: {
        std::normal_distribution<double> normal(0.5, 0.1);
        while (points.size() < count) {
            const double x = normal(random);
            const double y = normal(random);
            if (x >= 0.0 && x <= 1.0 && y >= 0.0 && y <= 1.0)
                points.push_back(withHeight(x, y));
        }
        break;
    }
    case Distribution::Cluster: {
        constexpr int kClusters = 10;
        std::vector<Point2> centres;
        for (int c = 0; c < kClusters; ++c)
            centres.push_back({unit(random), unit(random)});
        std::normal_distribution<double> spread(0.0, 0.01);
        for (std::size_t i = 0; i < count; ++i) {
            const Point2& centre = centres[i % kClusters];
            points.push_back(withHeight(centre.x + spread(random), centre.y + spread(random)));
        }
        break;
    }
    case Distribution::Grid: {
        const auto side = static_cast<std::size_t>(std::ceil(std::sqrt(static_cast<double>(count))));
        for (std::size_t row = 0; row < side; ++row)
            for (std::size_t col = 0; col < side; ++col)
                points.push_back(withHeight(static_cast<double>(col) / static_cast<double>(side),
                                            static_cast<double>(row) / static_cast<double>(side)));
        break;
    }
    case Distribution::Arc:
        for (std::size_t i = 0; i < count; ++i) {
            const double angle = std::numbers::pi * unit(random);
            points.push_back(withHeight(0.5 + 0.5 * std::cos(angle), 0.5 * std::sin(angle)));
        }
        break;
    }
    return points;
}

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
            const auto y = static_cast<long>(std::llround(std::sqrt(static_cast<double>(ySquared))));
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

#include "distributions.hpp"

#include <array>
#include <cmath>
#include <numbers>
#include <random>

namespace terratin::bench {

namespace {

// The elevation only travels with the points; a smooth terrain keeps it plausible.
Point3 withHeight(double x, double y) {
    return {x, y, 100.0 * std::sin(3.0 * x) * std::cos(2.0 * y)};
}

bool insideUnitSquare(double x, double y) {
    return x >= 0.0 && x <= 1.0 && y >= 0.0 && y <= 1.0;
}

} // namespace

std::string_view toString(Distribution distribution) {
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

std::optional<Distribution> parseDistribution(std::string_view name) {
    for (const Distribution distribution : kAllDistributions)
        if (toString(distribution) == name)
            return distribution;
    return std::nullopt;
}

std::vector<Point3> generatePoints(Distribution distribution, std::size_t count,
                                   std::uint64_t seed) {
    std::mt19937_64 random(seed);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    std::vector<Point3> points;
    points.reserve(count);
    switch (distribution) {
    case Distribution::Uniform:
        while (points.size() < count)
            points.push_back(withHeight(unit(random), unit(random)));
        break;
    case Distribution::Gauss: {
        std::normal_distribution<double> normal(0.5, 0.1);
        while (points.size() < count) {
            const double x = normal(random);
            const double y = normal(random);
            if (insideUnitSquare(x, y))
                points.push_back(withHeight(x, y));
        }
        break;
    }
    case Distribution::Cluster: {
        constexpr std::size_t kClusters = 10;
        std::array<Point2, kClusters> centres;
        for (Point2& centre : centres)
            centre = {unit(random), unit(random)};
        std::normal_distribution<double> spread(0.0, 0.01);
        while (points.size() < count) {
            const Point2& centre = centres[points.size() % kClusters];
            const double x = centre.x + spread(random);
            const double y = centre.y + spread(random);
            if (insideUnitSquare(x, y))
                points.push_back(withHeight(x, y));
        }
        break;
    }
    case Distribution::Grid: {
        const auto side =
            static_cast<std::size_t>(std::llround(std::sqrt(static_cast<double>(count))));
        const auto spacing = 1.0 / static_cast<double>(side);
        points.reserve(side * side);
        for (std::size_t row = 0; row < side; ++row)
            for (std::size_t col = 0; col < side; ++col)
                points.push_back(withHeight(static_cast<double>(col) * spacing,
                                            static_cast<double>(row) * spacing));
        break;
    }
    case Distribution::Arc:
        while (points.size() < count) {
            const double angle = std::numbers::pi * unit(random);
            points.push_back(withHeight(0.5 + 0.5 * std::cos(angle), 0.5 * std::sin(angle)));
        }
        break;
    }
    return points;
}

} // namespace terratin::bench

#include "terratin/triangulate/point_set.hpp"

#include "terratin/error.hpp"
#include "terratin/geometry/predicates.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <string>

namespace terratin {

namespace {

// Vertex ids are 32-bit and the triangulator reserves ids for its two symbolic vertices and a
// "none" marker, so the input must leave room for them.
constexpr std::size_t kMaxPoints = std::numeric_limits<std::uint32_t>::max() - 4;

void checkFinite(std::span<const Point3> points) {
    for (std::size_t i = 0; i < points.size(); ++i) {
        const Point3& p = points[i];
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
            throw InvalidInputError("Triangulator: point " + std::to_string(i) +
                                    " has a non-finite coordinate or elevation");
    }
}

// Groups of indices sharing (x, y) exactly, as runs of a sorted index array.
std::vector<std::uint32_t> sortedByPosition(std::span<const Point3> points) {
    std::vector<std::uint32_t> order(points.size());
    std::iota(order.begin(), order.end(), 0U);
    std::sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
        const Point3& p = points[a];
        const Point3& q = points[b];
        if (p.x != q.x)
            return p.x < q.x;
        if (p.y != q.y)
            return p.y < q.y;
        return a < b;
    });
    return order;
}

double mergedZ(std::span<const Point3> points, std::span<const std::uint32_t> group,
               DuplicateZPolicy policy) {
    switch (policy) {
    case DuplicateZPolicy::First:
        return points[group.front()].z;
    case DuplicateZPolicy::Last:
        return points[group.back()].z;
    case DuplicateZPolicy::Min: {
        double z = points[group.front()].z;
        for (std::uint32_t i : group)
            z = std::min(z, points[i].z);
        return z;
    }
    case DuplicateZPolicy::Max: {
        double z = points[group.front()].z;
        for (std::uint32_t i : group)
            z = std::max(z, points[i].z);
        return z;
    }
    case DuplicateZPolicy::Mean: {
        double sum = 0.0;
        for (std::uint32_t i : group)
            sum += points[i].z;
        return sum / static_cast<double>(group.size());
    }
    }
    return points[group.front()].z;
}

// True when value - origin is exactly representable (Knuth's TwoDiff error term is zero).
bool subtractsExactly(double value, double origin) {
    const double difference = value - origin;
    const double originVirtual = value - difference;
    const double valueVirtual = difference + originVirtual;
    const double error = (value - valueVirtual) + (originVirtual - origin);
    return error == 0.0;
}

// Centre of [lo, hi] rounded to a multiple of the ulp of the largest magnitude in the range, so
// that it is a multiple of every input's ulp: then x - origin is exact whenever it is not
// larger than x itself, which holds for data far from zero (UTM coordinates, say).
double roundedCentre(double lo, double hi) {
    const double centre = lo + (hi - lo) / 2.0;
    const double largest = std::max(std::abs(lo), std::abs(hi));
    if (largest == 0.0)
        return 0.0;
    const double ulp = std::nextafter(largest, std::numeric_limits<double>::infinity()) - largest;
    return std::round(centre / ulp) * ulp;
}

Point2 chooseOrigin(std::span<const Point3> points, std::span<const std::uint32_t> distinct) {
    double minX = std::numeric_limits<double>::infinity();
    double minY = minX;
    double maxX = -minX;
    double maxY = -minX;
    for (std::uint32_t i : distinct) {
        minX = std::min(minX, points[i].x);
        maxX = std::max(maxX, points[i].x);
        minY = std::min(minY, points[i].y);
        maxY = std::max(maxY, points[i].y);
    }
    Point2 origin{roundedCentre(minX, maxX), roundedCentre(minY, maxY)};
    for (std::uint32_t i : distinct) {
        if (!subtractsExactly(points[i].x, origin.x))
            origin.x = 0.0;
        if (!subtractsExactly(points[i].y, origin.y))
            origin.y = 0.0;
    }
    return origin;
}

// The exact predicates' range (predicates.hpp): beyond it their products could overflow or
// underflow and the sign would no longer be exact.
constexpr double kSmallestCoordinate = 1e-60;
constexpr double kLargestCoordinate = 1e70;

void requirePredicateRange(const std::vector<Point2>& local) {
    const auto outside = [](double value) {
        const double magnitude = std::abs(value);
        return magnitude != 0.0 && (magnitude < kSmallestCoordinate || magnitude > kLargestCoordinate);
    };
    for (const Point2& p : local)
        if (outside(p.x) || outside(p.y))
            throw InvalidInputError("Triangulator: coordinate (" + std::to_string(p.x) + ", " +
                                    std::to_string(p.y) +
                                    ") is outside the supported magnitude range 1e-60 .. 1e70");
}

void requireTwoDimensions(const std::vector<Point2>& local) {
    if (local.size() >= 3) {
        const Point2& a = local[0];
        const Point2& b = local[1];
        for (std::size_t i = 2; i < local.size(); ++i)
            if (predicates::orient2d(a, b, local[i]) != 0.0)
                return;
    }
    throw InvalidInputError("Triangulator: need at least three distinct points that are not all "
                            "on one line (got " +
                            std::to_string(local.size()) + " distinct points" +
                            (local.size() >= 3 ? ", all collinear)" : ")"));
}

} // namespace

PreparedPoints preparePoints(std::span<const Point3> points, DuplicateZPolicy policy) {
    if (points.size() > kMaxPoints)
        throw InvalidInputError("Triangulator: too many points (" + std::to_string(points.size()) +
                                "); at most " + std::to_string(kMaxPoints) + " are supported");
    checkFinite(points);

    const std::vector<std::uint32_t> order = sortedByPosition(points);

    // Walk the runs of equal (x, y); each run becomes one distinct point.
    struct Survivor {
        std::uint32_t firstIndex; // orders the distinct points like their first occurrence
        std::uint32_t source;
        double z;
    };
    std::vector<Survivor> survivors;
    survivors.reserve(points.size());
    PreparedPoints prepared;
    for (std::size_t begin = 0; begin < order.size();) {
        std::size_t end = begin + 1;
        const Point3& first = points[order[begin]];
        while (end < order.size() && points[order[end]].x == first.x &&
               points[order[end]].y == first.y)
            ++end;
        const std::span<const std::uint32_t> group(order.data() + begin, end - begin);
        const std::uint32_t source =
            policy == DuplicateZPolicy::Last ? group.back() : group.front();
        survivors.push_back({group.front(), source, mergedZ(points, group, policy)});
        prepared.duplicateCount += group.size() - 1;
        begin = end;
    }
    // Distinct points in input order, so results do not depend on the sort above.
    std::sort(survivors.begin(), survivors.end(),
              [](const Survivor& a, const Survivor& b) { return a.firstIndex < b.firstIndex; });

    prepared.sourceIndex.reserve(survivors.size());
    prepared.z.reserve(survivors.size());
    for (const Survivor& s : survivors) {
        prepared.sourceIndex.push_back(s.source);
        prepared.z.push_back(s.z);
    }
    prepared.origin = chooseOrigin(points, prepared.sourceIndex);
    prepared.local.reserve(survivors.size());
    for (std::uint32_t i : prepared.sourceIndex)
        prepared.local.push_back({points[i].x - prepared.origin.x, points[i].y - prepared.origin.y});

    requirePredicateRange(prepared.local);
    requireTwoDimensions(prepared.local);
    return prepared;
}

} // namespace terratin

// TinLocator: polylines clipped to the TIN's convex hull and draped on its surface
// (tin_locator.hpp), beside tin_locator.cpp's point location.

#include "terratin/triangulate/tin_locator.hpp"

#include "../parallel/parallel_for.hpp"
#include "hull_interior.hpp"

#include <algorithm>
#include <cmath>
#include <optional>

namespace terratin {

namespace {

Point2 planar(const Point3& p) {
    return {p.x, p.y};
}

Point3 along(const Point3& a, const Point3& b, double t) {
    return {a.x + t * (b.x - a.x), a.y + t * (b.y - a.y), a.z + t * (b.z - a.z)};
}

} // namespace

TinLocator::Interval TinLocator::hullInterval(const Point3& a, const Point3& b) const {
    Interval interval;
    for (const auto& [u, v] : *m_hullEdges) {
        const Point3& from = m_mesh->vertices[u];
        const Point3& to = m_mesh->vertices[v];
        const auto side = [&](const Point3& p) {
            return (to.x - from.x) * (p.y - from.y) - (to.y - from.y) * (p.x - from.x);
        };
        const double atA = side(a);
        const double atB = side(b);
        if (atA < 0.0 && atB < 0.0)
            return {1.0, 0.0}; // wholly outside this edge
        if (atA < 0.0)
            interval.enter = std::max(interval.enter, atA / (atA - atB));
        else if (atB < 0.0)
            interval.exit = std::min(interval.exit, atA / (atA - atB));
    }
    return interval;
}

TinLocator::LocatedPoint TinLocator::cutPoint(const Point3& inside, const Point3& outside) {
    const double exit = hullInterval(inside, outside).exit;
    // Back towards `inside` until the exact test agrees, by steps that double from one unit in
    // the last place of the parameter; `inside` itself ends the search.
    double step = std::numeric_limits<double>::epsilon();
    for (double t = exit; t > 0.0; t -= step, step *= 2.0) {
        const Point3 point = along(inside, outside, t);
        if (const std::optional<std::uint32_t> triangle = locate(planar(point)))
            return {point, *triangle};
    }
    return {inside, locate(planar(inside)).value()};
}

std::optional<Point3> TinLocator::pointInside(const Point3& a, const Point3& b) {
    const Interval interval = hullInterval(a, b);
    if (interval.enter >= interval.exit)
        return std::nullopt;
    const Point3 middle = along(a, b, 0.5 * (interval.enter + interval.exit));
    if (!locate(planar(middle)))
        return std::nullopt; // a touch too slight for double to place a point inside
    return middle;
}

std::vector<TinLocator::LocatedPolyline>
TinLocator::clipLocated(const std::vector<Point3>& polyline) {
    std::vector<LocatedPolyline> parts;
    LocatedPolyline part;
    const auto add = [&](const LocatedPoint& located) {
        part.points.push_back(located.point);
        part.triangles.push_back(located.triangle);
    };
    const auto closePart = [&] {
        if (part.points.size() >= 2)
            parts.push_back(std::move(part));
        part = {};
    };
    bool previousInside = false;
    for (std::size_t i = 0; i < polyline.size(); ++i) {
        const Point3& point = polyline[i];
        if (previousInside && !std::isnan(point.z) && m_interior &&
            m_interior->holds(planar(point))) {
            add({point, kUnlocated});
            continue;
        }
        const std::optional<std::uint32_t> triangle = locate(planar(point));
        if (triangle) {
            if (i > 0 && !previousInside) { // entering the hull
                add(cutPoint(point, polyline[i - 1]));
                part.enteredFrom = planar(polyline[i - 1]);
            }
            add({point, *triangle});
        } else if (previousInside) {
            add(cutPoint(polyline[i - 1], point)); // leaving it
            part.leftTowards = planar(point);
            closePart();
        } else if (i > 0) {
            // Both ends outside: the segment may still cross the hull.
            if (const std::optional<Point3> middle = pointInside(polyline[i - 1], point)) {
                add(cutPoint(*middle, polyline[i - 1]));
                add(cutPoint(*middle, point));
                part.enteredFrom = planar(polyline[i - 1]);
                part.leftTowards = planar(point);
                closePart();
            }
        }
        previousInside = triangle.has_value();
    }
    closePart();
    return parts;
}

std::vector<std::vector<Point3>> TinLocator::clipToHull(const std::vector<Point3>& polyline) {
    std::vector<std::vector<Point3>> parts;
    for (LocatedPolyline& part : clipLocated(polyline))
        parts.push_back(std::move(part.points));
    return parts;
}

std::vector<TinLocator::LocatedPolyline>
TinLocator::clipToSurface(const std::vector<Point3>& polyline) {
    std::vector<LocatedPolyline> parts = clipLocated(polyline);
    for (LocatedPolyline& part : parts)
        for (std::size_t i = 0; i < part.points.size(); ++i) {
            Point3& point = part.points[i];
            if (std::isnan(point.z))
                point.z = elevationIn(part.triangles[i], planar(point));
        }
    return parts;
}

std::vector<std::vector<TinLocator::LocatedPolyline>>
TinLocator::clipToSurface(const std::vector<std::vector<Point3>>& polylines,
                          unsigned threads) const {
    std::vector<std::vector<LocatedPolyline>> located(polylines.size());
    // A few polylines per chunk: their lengths differ, so the threads take chunks in turn, and
    // a chunk of one would have them meet at the counter for every polyline.
    constexpr std::size_t kPolylinesPerChunk = 16;
    detail::forChunksInTurn(polylines.size(), threads, kPolylinesPerChunk,
                            [&](std::size_t begin, std::size_t end) {
                                TinLocator walker = *this; // the walk's state is the chunk's
                                for (std::size_t i = begin; i < end; ++i) {
                                    walker.m_last = 0;
                                    walker.m_random = kWalkSeed;
                                    located[i] = walker.clipToSurface(polylines[i]);
                                }
                            });
    return located;
}

} // namespace terratin

#pragma once
/// @file
/// An axis-aligned bounding box in the plane.

#include "terratin/geometry/point.hpp"

#include <algorithm>
#include <limits>

namespace terratin::detail {

/// An axis-aligned box; empty (maxX < minX) until a point is added.
struct Box {
    double minX = std::numeric_limits<double>::infinity();
    double minY = std::numeric_limits<double>::infinity();
    double maxX = -std::numeric_limits<double>::infinity();
    double maxY = -std::numeric_limits<double>::infinity();

    void add(const Box& other) {
        minX = std::min(minX, other.minX);
        minY = std::min(minY, other.minY);
        maxX = std::max(maxX, other.maxX);
        maxY = std::max(maxY, other.maxY);
    }
    void add(const Point2& p) { add(Box{p.x, p.y, p.x, p.y}); }
    void add(const Point3& p) { add(Box{p.x, p.y, p.x, p.y}); }

    [[nodiscard]] bool empty() const { return maxX < minX || maxY < minY; }
};

} // namespace terratin::detail

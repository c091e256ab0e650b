#pragma once
/// @file
/// Floating-point geometry for the circum-circle method's conflict test: a worker skips the
/// other workers whose region (the box of the points they insert this round) a triangle's
/// circumcircle cannot reach, without reading their active points. A filter in front of a
/// hint: the owner tags, not these tests, keep every triangle to one worker.

#include "box.hpp"

#include "terratin/geometry/point.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace terratin::detail {

/// A circle, or the whole plane (infinite radius) when it could not be computed reliably.
struct Circle {
    double x = 0.0;
    double y = 0.0;
    double radius2 = std::numeric_limits<double>::infinity();

    /// The circumcircle of a, b, c; the whole plane when they are (nearly) collinear.
    static Circle through(const Point2& a, const Point2& b, const Point2& c) {
        const double bx = b.x - a.x;
        const double by = b.y - a.y;
        const double cx = c.x - a.x;
        const double cy = c.y - a.y;
        const double twiceArea2 = 2.0 * (bx * cy - by * cx);
        const double b2 = bx * bx + by * by;
        const double c2 = cx * cx + cy * cy;
        if (!(std::fabs(twiceArea2) > 1e-12 * (b2 + c2)))
            return {};
        const double ux = (cy * b2 - by * c2) / twiceArea2;
        const double uy = (bx * c2 - cx * b2) / twiceArea2;
        return {a.x + ux, a.y + uy, ux * ux + uy * uy};
    }

    /// Whether the closed disc may meet the box. Generous by a relative 1e-6 of the squared
    /// radius, far above the rounding of the centre's computation.
    [[nodiscard]] bool mayReach(const Box& box) const {
        if (box.empty())
            return false;
        if (radius2 == std::numeric_limits<double>::infinity())
            return true;
        const double dx = std::max({box.minX - x, 0.0, x - box.maxX});
        const double dy = std::max({box.minY - y, 0.0, y - box.maxY});
        return dx * dx + dy * dy <= radius2 * (1.0 + 1e-6);
    }
};

} // namespace terratin::detail

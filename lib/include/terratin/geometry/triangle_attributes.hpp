#pragma once
/// @file
/// Terrain attributes of one TIN triangle, computed from its plane.

#include "terratin/geometry/point.hpp"

namespace terratin {

/// Attributes of a triangle whose x, y are in a projected CRS and z in the same length unit.
struct TriangleAttributes {
    double zMin = 0.0;
    double zMax = 0.0;
    double zMean = 0.0;
    /// Angle between the triangle's plane and the horizontal, degrees in [0, 90].
    double slopeDeg = 0.0;
    /// Compass direction the plane faces downhill, degrees clockwise from grid north in
    /// [0, 360); -1 for a flat (horizontal) triangle.
    double aspectDeg = -1.0;
    /// Planimetric (x, y) area in squared CRS units.
    double area2d = 0.0;
};

/// Attributes of the triangle a, b, c (any orientation; a degenerate triangle gets slope 0,
/// aspect -1, area 0).
TriangleAttributes computeTriangleAttributes(const Point3& a, const Point3& b, const Point3& c);

} // namespace terratin

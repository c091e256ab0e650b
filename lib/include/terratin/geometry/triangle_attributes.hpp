#pragma once
/// @file
/// Terrain attributes of one TIN triangle, computed from its plane.

#include "terratin/geometry/point.hpp"

namespace terratin {

/// Attributes of a triangle whose x, y are in a projected CRS and z in the same length unit.
struct TriangleAttributes {
    /// Elevations of the corners, in the order the corners were given.
    double z1 = 0.0;
    double z2 = 0.0;
    double z3 = 0.0;
    double zMin = 0.0;
    double zMax = 0.0;
    double zMean = 0.0;
    /// Angle between the triangle's plane and the horizontal, degrees in [0, 90].
    double slopeDeg = 0.0;
    /// Slope as a percentage: 100 * rise / run = 100 * tan(slope); 100 at 45 degrees.
    double slopePct = 0.0;
    /// Compass direction the plane faces downhill, degrees clockwise from grid north in
    /// [0, 360); -1 for a flat (horizontal) triangle.
    double aspectDeg = -1.0;
    /// Planimetric (x, y) area in squared CRS units.
    double area2d = 0.0;
    /// Area of the triangle in 3D (the surface area), in squared CRS units; >= area2d.
    double area3d = 0.0;
    /// Unit normal of the plane, turned up (nz >= 0); (0, 0, 1) for a horizontal triangle.
    double nx = 0.0;
    double ny = 0.0;
    double nz = 0.0;
};

/// Attributes of the triangle a, b, c (any orientation).
/// A triangle without planimetric extent (corners collinear in x, y) gets slope 0, slope_pct 0,
/// aspect -1 and area_2d 0; its area_3d and normal are those of its (vertical) plane, the
/// normal turned so that its first non-zero component is positive, or (0, 0, 0) when the
/// corners are collinear in 3D as well.
/// A sliver, a triangle whose height over its longest edge (x, y) is at most 64 ulps of its
/// largest coordinate (points collinear in exact arithmetic that rounding moved apart: the
/// border of a rotated raster's TIN), gets slope 0, slope_pct 0 and aspect -1
/// as well: its slope would only measure the rounding (up to 1e15 %). Its area_2d (tiny,
/// positive), area_3d and normal are computed as for any triangle, so the areas still sum to
/// the hull's. The TIN keeps such triangles: they are exactly Delaunay, and the hull of the
/// rounded coordinates is exact.
/// Complexity: O(1), two atan2 and two hypot.
TriangleAttributes computeTriangleAttributes(const Point3& a, const Point3& b, const Point3& c);

} // namespace terratin

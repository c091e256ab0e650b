#pragma once
/// @file
/// Plain point types. Coordinates are in the units of the input CRS (metres for a projected
/// CRS); z is the elevation in the input's vertical units.

namespace terratin {

/// A planar point.
struct Point2 {
    double x = 0.0;
    double y = 0.0;

    friend bool operator==(const Point2&, const Point2&) = default;
};

/// A point with an elevation.
struct Point3 {
    double x = 0.0;
    double y = 0.0;
    double z = 0.0;

    friend bool operator==(const Point3&, const Point3&) = default;
};

} // namespace terratin

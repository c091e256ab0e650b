/// @file
/// Triangle attributes from the plane through three points.
///
/// Notation: with e1 = b - a and e2 = c - a, the normal is n = e1 x e2. For the plane
/// z = p x + q y + r through the triangle, p = -nx / nz and q = -ny / nz, so the downhill
/// direction -(p, q) is parallel to (nx, ny) once n is turned to point up (nz > 0). Then
///   slope     = atan(|grad z|) = atan2(hypot(nx, ny), nz)
///   slope_pct = 100 |grad z|   = 100 hypot(nx, ny) / nz
///   aspect    = atan2(east, north) of the downhill direction = atan2(nx, ny), clockwise from
///               grid north (the usual GIS convention, e.g. Burrough & McDonnell, "Principles
///               of Geographical Information Systems", 1998, ch. 8)
///   area2d    = |nz| / 2,   area3d = |n| / 2,   unit normal = n / |n|.
/// Turning n up makes every result independent of the corner order (CW or CCW).
/// A triangle within rounding of no planimetric extent (a sliver of points collinear in exact
/// arithmetic; see kFlatHeightUlps) gets the slope and aspect of one without extent.
/// Every quantity is a correctly rounded operation (or hypot / atan2) of the exact-as-possible
/// cross product, so Pythagorean test triangles give exact areas, normals and percentages.

#include "terratin/geometry/triangle_attributes.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace terratin {

namespace {
constexpr double kDegreesPerRadian = 180.0 / std::numbers::pi;

// A triangle whose height over its longest edge (x, y) is below this many units in the last
// place of its largest coordinate is flat in x, y as far as its input can tell: a vertex is
// known to about an ulp of its coordinates (a cell centre from a geotransform is off its
// exact position by two or three roundings, a reprojected point by more), so three points
// that are collinear in exact arithmetic come out with a height of a few ulps at most. A
// rotated grid's border gives such slivers (heights of 1e-11 m at UTM northings, 1.3e15 %
// slope). 64 ulps leaves a margin over those roundings and is still
// 3e-8 m at a northing of 5e6 m, far below any real triangle of terrain.
constexpr double kFlatHeightUlps = 64.0;

// Whether the triangle with planimetric doubled area `doubleArea` (= nz) is within rounding
// of having no planimetric extent.
bool isPlanimetricSliver(const Point3& a, const Point3& b, const Point3& c, double doubleArea) {
    const double longest =
        std::max({std::hypot(b.x - a.x, b.y - a.y), std::hypot(c.x - b.x, c.y - b.y),
                  std::hypot(a.x - c.x, a.y - c.y)});
    const double magnitude = std::max(
        {std::abs(a.x), std::abs(a.y), std::abs(b.x), std::abs(b.y), std::abs(c.x), std::abs(c.y)});
    const double tolerance = kFlatHeightUlps * std::numeric_limits<double>::epsilon() * magnitude;
    // height = doubleArea / longest; compared without the division.
    return doubleArea <= tolerance * longest;
}
/// The cross product (b - a) x (c - a), turned up (see the notation above).
struct Normal {
    double x;
    double y;
    double z;
};

Normal upwardNormal(const Point3& a, const Point3& b, const Point3& c) {
    // Edges relative to a: projected coordinates are large (UTM northings ~5e6), their
    // differences are small and nearly exact, so the cross product keeps its precision.
    const double e1x = b.x - a.x;
    const double e1y = b.y - a.y;
    const double e1z = b.z - a.z;
    const double e2x = c.x - a.x;
    const double e2y = c.y - a.y;
    const double e2z = c.z - a.z;
    Normal n{e1y * e2z - e1z * e2y, e1z * e2x - e1x * e2z, e1x * e2y - e1y * e2x};
    // Up, or for a vertical plane the first non-zero component positive: a canonical sign
    // that does not depend on the corner order.
    if (n.z < 0.0 || (n.z == 0.0 && (n.x < 0.0 || (n.x == 0.0 && n.y < 0.0))))
        n = {-n.x, -n.y, -n.z};
    return n;
}

/// The compass direction, degrees clockwise from grid north in [0, 360), of the downhill
/// direction (nx, ny), which is not (0, 0).
double aspectDegrees(double nx, double ny) {
    double aspect = std::atan2(nx, ny) * kDegreesPerRadian;
    if (aspect < 0.0)
        aspect += 360.0;
    // A direction a hair west of north gives a tiny negative angle, and -tiny + 360 rounds to
    // 360, which is outside [0, 360): it is north.
    if (aspect >= 360.0)
        aspect = 0.0;
    return aspect;
}

/// Slope and aspect of a triangle that has none (the header's convention).
void setNoSlope(TriangleAttributes& attributes) {
    attributes.slopeDeg = 0.0;
    attributes.slopePct = 0.0;
    attributes.aspectDeg = -1.0;
}

} // namespace

TriangleAttributes computeTriangleAttributes(const Point3& a, const Point3& b, const Point3& c) {
    TriangleAttributes attributes;
    attributes.z1 = a.z;
    attributes.z2 = b.z;
    attributes.z3 = c.z;
    attributes.zMin = std::min({a.z, b.z, c.z});
    attributes.zMax = std::max({a.z, b.z, c.z});
    attributes.zMean = (a.z + b.z + c.z) / 3.0;

    const Normal n = upwardNormal(a, b, c);
    const double horizontal = std::hypot(n.x, n.y);
    const double length = std::hypot(horizontal, n.z);
    attributes.area3d = 0.5 * length;
    if (length > 0.0) {
        attributes.nx = n.x / length;
        attributes.ny = n.y / length;
        attributes.nz = n.z / length;
    }

    // No planimetric extent (collinear in x, y): the plane is vertical or undefined, so slope
    // and aspect have no meaning; the header documents slope 0, aspect -1, area 0.
    if (n.z == 0.0) {
        setNoSlope(attributes);
        attributes.area2d = 0.0;
        return attributes;
    }

    attributes.area2d = 0.5 * n.z;
    // Within rounding of no extent: the same slope and aspect as above, the (tiny) area kept
    // so that areas still sum to the hull's.
    if (isPlanimetricSliver(a, b, c, n.z)) {
        setNoSlope(attributes);
        return attributes;
    }
    attributes.slopeDeg = std::atan2(horizontal, n.z) * kDegreesPerRadian;
    attributes.slopePct = 100.0 * (horizontal / n.z);
    // Exact comparison on purpose: a horizontal triangle (all z equal) gives nx = ny = 0
    // exactly, and any tilt at all, however small, has a well-defined downhill direction.
    attributes.aspectDeg = n.x == 0.0 && n.y == 0.0 ? -1.0 : aspectDegrees(n.x, n.y);
    return attributes;
}

} // namespace terratin

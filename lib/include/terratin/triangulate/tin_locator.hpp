#pragma once
/// @file
/// Queries of a finished TIN by position: the triangle holding a point, the TIN's elevation
/// there, and polylines clipped to the TIN's convex hull (breaklines on the data's extent).

#include "terratin/geometry/point.hpp"
#include "terratin/triangulate/tin_mesh.hpp"

#include <array>
#include <cstdint>
#include <optional>
#include <vector>

namespace terratin {

/// Locates points in a TinMesh that covers its convex hull (as triangulate() makes it) by
/// walking from the triangle found last, or from a bucket grid's triangle when that is nearer:
/// queries along a line cost O(triangles crossed), a jump O(1) expected for evenly spread
/// vertices. Every side test is exact (orient2d). Holds a pointer to the mesh, which must outlive
/// it and stay unchanged.
class TinLocator {
public:
    explicit TinLocator(const TinMesh& mesh);

    /// A triangle holding `point` (inside or on its boundary); nullopt when the point lies
    /// outside the convex hull.
    [[nodiscard]] std::optional<std::uint32_t> locate(Point2 point);

    /// The TIN's elevation at `point`, linear in the triangle holding it; nullopt outside the
    /// convex hull.
    [[nodiscard]] std::optional<double> elevation(Point2 point);

    /// The parts of `polyline` inside the convex hull (on its boundary counts as inside), in
    /// order. A segment crossing the hull is cut where it crosses: the cut point is computed in
    /// double along the segment, then moved towards the inside point by as many units in the
    /// last place as it takes for the exact test to find it inside (a few at most), so that
    /// every point of the result is inside. z of a cut point is interpolated along the
    /// segment (NaN stays NaN). Parts of a single point are dropped.
    [[nodiscard]] std::vector<std::vector<Point3>> clipToHull(const std::vector<Point3>& polyline);

private:
    /// The part [enter, exit] of the segment a + t (b - a), 0 <= t <= 1, on the inner side of
    /// every hull edge, in double: Cyrus and Beck's clipping against a convex polygon.
    struct Interval {
        double enter = 0.0;
        double exit = 1.0;
    };
    [[nodiscard]] Interval hullInterval(const Point3& a, const Point3& b) const;
    /// The last point of the segment from `inside` towards `outside` that the exact test finds
    /// inside the hull.
    [[nodiscard]] Point3 cutPoint(const Point3& inside, const Point3& outside);
    /// A point inside the hull on the segment a-b, whose ends are both outside; nullopt when
    /// it misses the hull.
    [[nodiscard]] std::optional<Point3> pointInside(const Point3& a, const Point3& b);

    /// A triangle near `point` to start a walk from: the bucket grid's.
    [[nodiscard]] std::uint32_t startNear(Point2 point) const;

    const TinMesh* m_mesh;
    std::uint32_t m_last = 0;
    /// A grid of buckets over the vertices' bounding box, each holding a triangle whose first
    /// corner lies in it (kNoTriangle for none): a walk starts a few triangles from its goal
    /// wherever the previous query was.
    static constexpr std::uint32_t kNoTriangle = 0xffffffffU;
    Point2 m_origin{};
    double m_bucketSize = 1.0;
    std::size_t m_columns = 0;
    std::size_t m_rows = 0;
    std::vector<std::uint32_t> m_buckets;
    /// The hull's edges as vertex pairs, counter-clockwise (the mesh's edges with no neighbour).
    std::vector<std::array<std::uint32_t, 2>> m_hullEdges;
};

} // namespace terratin

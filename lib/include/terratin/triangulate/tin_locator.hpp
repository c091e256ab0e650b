#pragma once
/// @file
/// Queries of a finished TIN by position: the triangle holding a point, the TIN's elevation
/// there, and polylines clipped to the TIN's convex hull (breaklines on the data's extent).

#include "terratin/geometry/point.hpp"
#include "terratin/triangulate/tin_mesh.hpp"

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

namespace terratin {

namespace detail {
class HullInterior;
}

/// Locates points in a TinMesh that covers its convex hull (as triangulate() or
/// insertConstraints make it) by a remembering stochastic walk (it ends on constrained
/// triangulations too) from the triangle found last, or from a bucket grid's triangle when that
/// is nearer: queries along a line cost O(triangles crossed), a jump O(1) expected for evenly
/// spread vertices. Every side test of locate() is exact (orient2d). Holds a pointer to the mesh,
/// which must outlive it and stay unchanged.
class TinLocator {
public:
    /// What the construction may rely on, and how the locator will be used.
    struct Use {
        /// Threads for the construction (0: all hardware threads; the result is the same for
        /// any).
        unsigned threads = 1;
        /// The mesh covers its convex hull, as triangulate() and insertConstraints make it (no
        /// triangle left out): the hull's edges are then found by walking to the hull and
        /// round it, O(sqrt(n) + hull), instead of a pass over every triangle.
        bool coversConvexHull = false;
        /// About how many queries will start far from the one before (each polyline's first
        /// point, as clipToSurface makes them); 0: about one per triangle. A few thousand need
        /// a grid of a few buckets each, quicker to fill than one per 16 triangles, whose
        /// longer walks cost less than the fill saves.
        std::size_t farQueries = 0;
    };

    /// Reads the mesh's hull edges and fills the bucket grid, on up to `threads` threads (0:
    /// all hardware threads; the result is the same for any). O(n).
    explicit TinLocator(const TinMesh& mesh, unsigned threads = 1);
    /// The same, as `use` allows.
    TinLocator(const TinMesh& mesh, const Use& use);

    /// A triangle holding `point` (inside or on its boundary); nullopt when the point lies
    /// outside the convex hull (at once outside the hull's bounding box).
    [[nodiscard]] std::optional<std::uint32_t> locate(Point2 point);

    /// A triangle holding `point` up to rounding: the side tests are orient2d's floating-point
    /// stage alone, and a point within its error bound of an edge counts as on it. Much faster
    /// than locate() where many points lie on edges (a grid's cells on a grid TIN's edges), for
    /// callers that only interpolate there. nullopt when the point lies surely outside the hull.
    [[nodiscard]] std::optional<std::uint32_t> locateNear(Point2 point);

    /// locateNear, walking from triangle `start` instead of the last one or the bucket grid's.
    /// The one query that may follow changes to the mesh (points inserted into it, which keep
    /// every triangle slot and add others), as long as it still covers its convex hull: from a
    /// point's old triangle the walk is short. A `start` past the last triangle: locateNear.
    [[nodiscard]] std::optional<std::uint32_t> locateNearFrom(Point2 point, std::uint32_t start);

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

    /// The TIN's elevation at `point`, linear in `triangle`, which holds it (as locate gives):
    /// the same to the last bit whichever triangle holding the point is given, and however its
    /// corners are stored (so the same for any numbering of the triangles).
    [[nodiscard]] double elevationIn(std::uint32_t triangle, Point2 point) const;

    /// In LocatedPolyline::triangles: no triangle was looked for.
    static constexpr std::uint32_t kUnlocated = 0xffffffffU;

    /// A part of a polyline inside the hull, with the triangle holding each of its points.
    struct LocatedPolyline {
        std::vector<Point3> points;
        /// triangles[i] holds points[i] (inside or on its boundary), as locate gives it, or is
        /// kUnlocated (see clipToSurface).
        std::vector<std::uint32_t> triangles;
        /// Where the part was cut (clipToHull): the polyline's point outside the hull that the
        /// segment cut at points.front() came from, and the one that the segment cut at
        /// points.back() went on to; nullopt at an end that is the polyline's own. A cut point
        /// lies inside the hull, or on it, up to a few units in the last place short of where
        /// the segment crosses it: a polygon's ring cut so does not reach the hull, and what
        /// closes the polygon there is the rest of that segment.
        std::optional<Point2> enteredFrom;
        std::optional<Point2> leftTowards;
    };

    /// The parts of clipToHull(polyline), each point with its triangle, and a NaN z replaced by
    /// the TIN's elevation there (elevationIn): each point is located once. Where the hull is
    /// one convex cycle (a mesh with no triangle left out), a point that has a z, follows a
    /// point inside and lies in a box known to be inside the hull (one per row of the bucket
    /// grid, checked by the exact test) is not located: its triangle is kUnlocated. Such a
    /// point is inside, and so is its segment from the point before (the hull is convex); a
    /// search for it may start from that point. The first point of a part is always located.
    [[nodiscard]] std::vector<LocatedPolyline> clipToSurface(const std::vector<Point3>& polyline);

    /// clipToSurface of every polyline, on up to `threads` threads (0: all hardware threads).
    /// Each polyline's walks start afresh, so the result does not depend on `threads`, nor on
    /// this locator's earlier queries.
    [[nodiscard]] std::vector<std::vector<LocatedPolyline>>
    clipToSurface(const std::vector<std::vector<Point3>>& polylines, unsigned threads) const;

private:
    /// A point of a clipped part and the triangle holding it.
    struct LocatedPoint {
        Point3 point;
        std::uint32_t triangle = 0;
    };
    /// clipToHull's parts, with the triangle of each point.
    [[nodiscard]] std::vector<LocatedPolyline> clipLocated(const std::vector<Point3>& polyline);

    /// The part [enter, exit] of the segment a + t (b - a), 0 <= t <= 1, on the inner side of
    /// every hull edge, in double: Cyrus and Beck's clipping against a convex polygon.
    struct Interval {
        double enter = 0.0;
        double exit = 1.0;
    };
    [[nodiscard]] Interval hullInterval(const Point3& a, const Point3& b) const;
    /// The last point of the segment from `inside` towards `outside` that the exact test finds
    /// inside the hull, and its triangle.
    [[nodiscard]] LocatedPoint cutPoint(const Point3& inside, const Point3& outside);
    /// A point inside the hull on the segment a-b, whose ends are both outside; nullopt when
    /// it misses the hull.
    [[nodiscard]] std::optional<Point3> pointInside(const Point3& a, const Point3& b);

    /// The walk of locate() and locateNear(): `outside(a, b, p)` says p lies beyond edge a-b.
    template <class OutsideOf>
    [[nodiscard]] std::optional<std::uint32_t> walk(Point2 point, OutsideOf outside);
    /// The walk itself, from triangle `start`.
    template <class OutsideOf>
    [[nodiscard]] std::optional<std::uint32_t> walkFrom(std::uint32_t start, Point2 point,
                                                        OutsideOf outside);

    /// Gives every empty bucket a triangle of a filled bucket near it.
    void fillEmptyBuckets(std::vector<std::uint32_t>& buckets) const;

    /// Each bucket with the first triangle, in index order, whose first corner lies in it, of
    /// every `stride`-th triangle.
    [[nodiscard]] std::vector<std::uint32_t> fillBuckets(std::size_t stride,
                                                         unsigned threads) const;
    /// A triangle near `point` to start a walk from: the bucket grid's.
    [[nodiscard]] std::uint32_t startNear(Point2 point) const;

    const TinMesh* m_mesh;
    std::uint32_t m_last = 0;
    /// The walk's random choices (a fixed sequence: the same queries give the same answers).
    static constexpr std::uint64_t kWalkSeed = 0x9e3779b97f4a7c15ULL;
    std::uint64_t m_random = kWalkSeed;
    /// A grid of buckets over the vertices' bounding box, each holding a triangle whose first
    /// corner lies in it or in a bucket near it: a walk starts a few triangles from its goal
    /// wherever the previous query was.
    static constexpr std::uint32_t kNoTriangle = 0xffffffffU;
    Point2 m_origin{};
    double m_bucketSize = 1.0;
    std::size_t m_columns = 0;
    std::size_t m_rows = 0;
    /// The buckets and the hull's edges are made once and shared by every copy: a copy, each
    /// thread's or each block of queries', then costs no memory.
    std::shared_ptr<const std::vector<std::uint32_t>> m_buckets;
    /// The hull's edges as vertex pairs, counter-clockwise (the mesh's edges with no neighbour).
    std::shared_ptr<const std::vector<std::array<std::uint32_t, 2>>> m_hullEdges;
    /// The top right corner of the hull's bounding box (m_origin is its bottom left).
    Point2 m_hullHigh{};
    /// Boxes inside the hull, one per row of buckets.
    std::shared_ptr<const detail::HullInterior> m_interior;
};

} // namespace terratin

#pragma once
// Boxes inside a TIN's convex hull, one per row of TinLocator's bucket grid: a point in one of
// them lies inside the hull without a walk through the mesh. Breakline points far from the
// data's edge (nearly all of them) then need no search of their own before insertConstraints,
// which finds each from the previous one.

#include "terratin/geometry/point.hpp"
#include "terratin/triangulate/tin_mesh.hpp"

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace terratin::detail {

class HullInterior {
public:
    HullInterior() = default;
    /// The boxes of `rows` rows of height `rowHeight` from origin.y up, from `hullEdges` (the
    /// mesh's edges with no neighbour, each with the mesh on its left). None when those edges
    /// are not one convex cycle (a mesh with triangles left out). Each box's corners are
    /// inside or on the hull by the exact test, so the box is too (the hull is convex).
    /// O(rows * hull vertices).
    HullInterior(const MeshArray<Point3>& vertices,
                 const std::vector<std::array<std::uint32_t, 2>>& hullEdges, Point2 origin,
                 double rowHeight, std::size_t rows);

    /// True: `point` lies inside the hull or on it, as the exact test would find. False says
    /// nothing. O(1).
    [[nodiscard]] bool holds(Point2 point) const;

private:
    struct Box {
        Point2 low;
        Point2 high; // low > high: an empty box
    };
    Point2 m_origin{};
    double m_rowHeight = 1.0;
    std::vector<Box> m_rows;
};

} // namespace terratin::detail

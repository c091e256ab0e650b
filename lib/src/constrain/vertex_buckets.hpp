#pragma once
// A coarse grid over the vertices, to start point location close to a point: the first point
// of each polyline may be anywhere, and a walk from an arbitrary triangle is O(sqrt(n)) steps.

#include "terratin/geometry/point.hpp"
#include "terratin/triangulate/tin_mesh.hpp"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace terratin::detail {

class VertexBuckets {
public:
    /// One bucket per kVerticesPerBucket vertices (about), over their bounding box; each keeps
    /// the first vertex that falls in it. O(n).
    explicit VertexBuckets(const MeshArray<Point3>& vertices);

    /// A vertex in the bucket of `p` (clamped to the grid), or in the nearest ring of buckets
    /// around it that holds one. Vertices added later are not known, but every vertex known
    /// stays a vertex. Precondition: at least one vertex.
    [[nodiscard]] std::uint32_t vertexNear(const Point2& p) const;

private:
    static constexpr std::size_t kVerticesPerBucket = 16;
    static constexpr std::uint32_t kEmpty = 0xffffffffU;

    [[nodiscard]] std::size_t column(double x) const;
    [[nodiscard]] std::size_t row(double y) const;

    Point2 m_min;
    double m_cellsPerUnitX = 0.0;
    double m_cellsPerUnitY = 0.0;
    std::size_t m_side = 1;
    std::vector<std::uint32_t> m_first;
};

} // namespace terratin::detail

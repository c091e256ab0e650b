#pragma once
// What the tiled refinement's tests check of a joined TIN: that it is one conforming
// triangulation (no crack, no T-junction, no overlap).

#include "terratin/geometry/point.hpp"
#include "terratin/triangulate/tin_mesh.hpp"

#include <cstddef>

namespace terratin::test {

inline Point2 xy(const Point3& p) {
    return {p.x, p.y};
}

/// What the conformity check counted.
struct EdgeCount {
    std::size_t interior = 0;
    std::size_t boundary = 0;
};

/// EXPECTs a conforming TIN: counter-clockwise triangles, no directed edge twice (two
/// triangles on one side of an edge: an overlap), and each edge with triangles on both sides
/// linked as neighbours both ways (else a crack or a T-junction would leave both open).
EdgeCount expectConforming(const TinMesh& mesh);

/// The sum of the triangles' signed areas.
double areaSum(const TinMesh& mesh);

} // namespace terratin::test

#pragma once
// The invariants every triangulation test checks.

#include "terratin/geometry/point.hpp"
#include "terratin/triangulate/tin_mesh.hpp"

#include <array>
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

namespace terratin::test {

/// Area of the convex hull of `points` (Andrew's monotone chain with exact orientation tests),
/// computed independently of the triangulator.
double convexHullArea(std::span<const Point3> points);

/// Sum of the triangles' planimetric areas.
double triangleAreaSum(const TinMesh& mesh);

/// Asserts (with gtest EXPECTs) that `mesh` is an exact Delaunay triangulation of `input`:
/// validateDelaunay finds nothing (CCW, twin symmetry, empty circle on every interior edge,
/// Euler, convex boundary), the vertices are exactly the distinct input points, and the
/// triangle areas add up to the convex hull's area.
void expectExactDelaunayOf(const TinMesh& mesh, std::span<const Point3> input);

/// A triangle as the (x, y) of its corners, sorted.
using CornerTriple = std::array<std::pair<double, double>, 3>;

/// The triangles (vertex index triples into `vertices`) as corner coordinates, each sorted and
/// all sorted: equal for two meshes with the same triangles, whatever their numbering.
std::vector<CornerTriple> sortedTriangles(std::span<const Point3> vertices,
                                          std::span<const std::uint32_t> triangles);

/// Asserts that `a` and `b` have the same triangles, compared by their corners' coordinates
/// whatever the order of triangles, of corners and of vertices.
void expectSameTriangles(const TinMesh& a, const TinMesh& b);

} // namespace terratin::test

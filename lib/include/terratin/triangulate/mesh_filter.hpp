#pragma once
/// @file
/// Removing triangles from a TinMesh: over holes, or with edges too long to be terrain (the
/// large triangles that bridge gaps in a point cloud's convex hull).

#include "terratin/triangulate/tin_mesh.hpp"

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace terratin {

/// Removes the triangles t with drop[t] != 0 (drop.size() == mesh.triangleCount()).
/// Kept triangles keep their corners and order; a neighbour link across a removed triangle
/// becomes kNoNeighbour; vertices no kept triangle uses are removed (sourceIndex follows).
/// Returns the number of triangles removed. O(vertices + triangles).
std::size_t dropTriangles(TinMesh& mesh, std::span<const std::uint8_t> drop);

/// drop[t] = 1 for the triangles with an edge longer than `maxEdge` (planimetric length in the
/// CRS's x, y units, > 0 and finite; InvalidInputError otherwise), 0 for the others.
std::vector<std::uint8_t> longEdgeTriangles(const TinMesh& mesh, double maxEdge);

/// Removes the triangles longEdgeTriangles marks, as dropTriangles does. Returns the number
/// removed.
std::size_t dropLongEdgeTriangles(TinMesh& mesh, double maxEdge);

} // namespace terratin

#pragma once
/// @file
/// The triangulation result as flat arrays (delaunator style), with no pointer graph.

#include "terratin/geometry/point.hpp"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace terratin {

/// Marks "no neighbour" (a convex hull edge) in TinMesh::neighbours.
inline constexpr std::int32_t kNoNeighbour = -1;

/// A triangulated irregular network.
///
/// - `vertices`: the distinct input points, in input units (the local origin used while
///   triangulating has been added back, so coordinates are exactly the input's).
/// - `sourceIndex[v]`: index in the caller's input array of the point that became vertex v.
/// - `triangles[3t+i]`: vertex index of corner i of triangle t; corners are counter-clockwise.
/// - `neighbours[3t+i]`: triangle across the edge from corner i to corner (i+1)%3, or
///   kNoNeighbour when that edge lies on the convex hull.
struct TinMesh {
    std::vector<Point3> vertices;
    std::vector<std::uint32_t> sourceIndex;
    std::vector<std::uint32_t> triangles;
    std::vector<std::int32_t> neighbours;

    [[nodiscard]] std::size_t triangleCount() const { return triangles.size() / 3; }
    [[nodiscard]] std::size_t vertexCount() const { return vertices.size(); }
};

} // namespace terratin

#pragma once
/// @file
/// A constrained Delaunay TIN: the mesh, which of its edges are constrained, and the chain of
/// vertices each input constraint became. docs/algorithms.md ("Constrained Delaunay") describes
/// how it is built.

#include "terratin/triangulate/tin_mesh.hpp"

#include <cstdint>
#include <limits>
#include <vector>

namespace terratin {

/// TinMesh::sourceIndex of a vertex made from a polyline point of a constraint (no input point
/// of the triangulation had its x and y).
inline constexpr std::uint32_t kConstraintPointSource =
    std::numeric_limits<std::uint32_t>::max() - 1;

/// TinMesh::sourceIndex of a vertex made where two constraints cross (see insertConstraints for
/// its coordinates and elevation).
inline constexpr std::uint32_t kIntersectionSource = std::numeric_limits<std::uint32_t>::max();

/// A TIN in which every constraint is a chain of edges.
///
/// - `mesh`: the same arrays and conventions as TinMesh; vertices added for constraints come
///   after the input's and have sourceIndex kConstraintPointSource or kIntersectionSource.
/// - `constrained[3t+i]`: 1 when the edge from corner i to corner (i+1)%3 of triangle t is
///   constrained, else 0; both half-edges of an interior edge carry the same flag. A MeshArray
///   like the mesh's own arrays: as long as `triangles`, and written at random places.
/// - `chains[k]`: the vertices input constraint k became, in order from its first point to its
///   last (ConstraintSet::segments first, then ConstraintSet::polylines); consecutive vertices
///   are joined by a constrained edge. A constraint of zero length is its one vertex. Where
///   rounding leaves several crossings within a few ulps of each other, a chain may run to one
///   of them and back over the same edge (insertConstraints).
struct ConstrainedTin {
    TinMesh mesh;
    MeshArray<std::uint8_t> constrained;
    std::vector<std::vector<std::uint32_t>> chains;
    /// Vertices added for polyline points and for crossings.
    std::size_t addedPoints = 0;
    std::size_t intersections = 0;
};

} // namespace terratin

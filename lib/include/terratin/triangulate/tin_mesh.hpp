#pragma once
/// @file
/// The triangulation result as flat arrays (delaunator style), with no pointer graph.

#include "terratin/detail/huge_page_allocator.hpp"
#include "terratin/geometry/point.hpp"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace terratin {

/// Marks "no neighbour" (a convex hull edge) in TinMesh::neighbours.
inline constexpr std::int32_t kNoNeighbour = -1;

/// The arrays of TinMesh: a std::vector in every use (data(), std::span, iteration, ==), whose
/// memory lies on 2 MiB pages once it is a megabyte or more, and whose resize() leaves new
/// elements of a trivial type unwritten (the triangulator sizes an array and then fills it on
/// all its threads). Its allocator is the library's (terratin::detail): name the type
/// MeshArray<T>, never the allocator.
template <class T> using MeshArray = std::vector<T, detail::HugePageArrayAllocator<T>>;

/// A triangulated irregular network.
///
/// - `vertices`: the distinct input points, in input units (the local origin used while
///   triangulating has been added back, so coordinates are exactly the input's).
/// - `sourceIndex[v]`: index in the caller's input array of the point that became vertex v.
/// - `triangles[3t+i]`: vertex index of corner i of triangle t; corners are counter-clockwise.
/// - `neighbours[3t+i]`: triangle across the edge from corner i to corner (i+1)%3, or
///   kNoNeighbour when that edge lies on the convex hull.
struct TinMesh {
    MeshArray<Point3> vertices;
    MeshArray<std::uint32_t> sourceIndex;
    MeshArray<std::uint32_t> triangles;
    MeshArray<std::int32_t> neighbours;

    [[nodiscard]] std::size_t triangleCount() const { return triangles.size() / 3; }
    [[nodiscard]] std::size_t vertexCount() const { return vertices.size(); }
};

/// Reserves, before `mesh` is filled, its arrays for `vertices` vertices and `spare` more,
/// with their triangles (fewer than two per vertex): inserting the spare ones later then copies
/// no array. The memory is only address space until it is written.
inline void reserveRoom(TinMesh& mesh, std::size_t vertices, std::size_t spare) {
    const std::size_t room = vertices + spare;
    mesh.vertices.reserve(room);
    mesh.sourceIndex.reserve(room);
    mesh.triangles.reserve(6 * room);
    mesh.neighbours.reserve(6 * room);
}

} // namespace terratin

#pragma once
/// @file
/// The triangulation result as flat arrays (delaunator style), with no pointer graph.

#include "terratin/geometry/point.hpp"
#include "terratin/huge_pages.hpp"

#include <cstddef>
#include <cstdint>
#include <new>
#include <utility>
#include <vector>

namespace terratin {

/// Marks "no neighbour" (a convex hull edge) in TinMesh::neighbours.
inline constexpr std::int32_t kNoNeighbour = -1;

/// The allocator of TinMesh's arrays: large ones on huge pages (huge_pages.hpp), and
/// resize() leaves new elements default-initialised. The triangulator sizes an array and
/// then fills it on all its threads; zeros written first by resize() would be a pass over
/// tens of megabytes on one thread (a tenth of a million-point triangulation).
template <class T> struct MeshAllocator : HugePageAllocator<T> {
    template <class U> struct rebind { using other = MeshAllocator<U>; };
    MeshAllocator() = default;
    template <class U> explicit MeshAllocator(const MeshAllocator<U>& /*other*/) noexcept {}

    /// Default-initialises (a no-op for the mesh's trivial types) where std::allocator
    /// value-initialises.
    template <class U> void construct(U* p) noexcept { ::new (static_cast<void*>(p)) U; }
    template <class U, class... Args> void construct(U* p, Args&&... args) {
        ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
    }
};

/// A vector whose resize() leaves new elements unwritten (see MeshAllocator).
template <class T> using MeshArray = std::vector<T, MeshAllocator<T>>;

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

} // namespace terratin

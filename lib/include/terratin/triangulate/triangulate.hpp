#pragma once
/// @file
/// The triangulation entry point of terratin::core: points in, Delaunay TIN out.

#include "terratin/geometry/point.hpp"
#include "terratin/progress.hpp"
#include "terratin/triangulate/point_set.hpp"
#include "terratin/triangulate/tin_mesh.hpp"

#include <cstddef>
#include <cstdint>
#include <span>

namespace terratin {

/// The order in which points are inserted.
enum class InsertionOrder {
    /// A uniformly random permutation: the paper's order.
    Random,
    /// Biased randomized insertion order: random rounds, each sorted along a Hilbert curve.
    /// Same expected complexity, far fewer cache misses in the DAG (several times faster on
    /// large inputs).
    Brio,
};

/// How to triangulate.
struct TriangulationOptions {
    /// Seed of the random insertion order. The same seed gives the same mesh.
    std::uint64_t seed = 1;
    InsertionOrder order = InsertionOrder::Brio;
    /// Which elevation survives for points sharing exactly the same (x, y).
    DuplicateZPolicy duplicateZ = DuplicateZPolicy::First;
};

/// A TIN and what it took to build it.
struct TriangulationResult {
    TinMesh mesh;
    std::size_t inputPoints = 0;
    /// Input points merged into another with exactly the same (x, y).
    std::size_t duplicatePoints = 0;
    /// Nodes in the point-location history (triangles ever created).
    std::size_t historyNodes = 0;
    /// Bytes reserved for the history.
    std::size_t historyBytes = 0;
};

/// Delaunay triangulation of `points` (x, y in any planar units; z carried along).
///
/// Postconditions: the triangles cover exactly the convex hull of the distinct points; every
/// distinct point is a vertex; across every interior edge the opposite vertex is never strictly
/// inside a triangle's circumcircle, decided with exact predicates (so the result is exactly
/// Delaunay; among cocircular points, as on grids, the diagonal choice follows the insertion
/// order). Throws InvalidInputError (non-finite values, fewer than three non-collinear points,
/// too many points) and Cancelled when `progress` returns false.
/// Complexity: expected O(n log n) time, O(n) memory (about 9 history nodes of 28 bytes per
/// point besides the mesh).
TriangulationResult triangulate(std::span<const Point3> points,
                                const TriangulationOptions& options = {},
                                const ProgressCallback& progress = {});

} // namespace terratin

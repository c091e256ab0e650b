#pragma once
/// @file
/// Preparing input points for triangulation: validation, exact duplicate merging and the shift
/// to a local origin.

#include "terratin/geometry/point.hpp"
#include "terratin/triangulate/tin_mesh.hpp"

#include <cstddef>
#include <cstdint>
#include <span>

namespace terratin {

/// Which elevation survives when several input points share exactly the same (x, y).
enum class DuplicateZPolicy {
    First, ///< the point that comes first in the input (the default)
    Last,  ///< the point that comes last in the input
    Min,   ///< the lowest elevation
    Max,   ///< the highest elevation
    Mean,  ///< the mean elevation of the group
};

/// Distinct input points ready for the triangulator, in arrays like the mesh's (MeshArray).
struct PreparedPoints {
    /// Planar coordinates minus `origin`, exactly (see prepareOrigin).
    MeshArray<Point2> local;
    /// Elevation of each distinct point after the duplicate policy.
    MeshArray<double> z;
    /// Input index of the point each distinct point stands for (the first of its group for
    /// the Min, Max and Mean policies).
    MeshArray<std::uint32_t> sourceIndex;
    /// Added to `local` gives the input coordinates back exactly.
    Point2 origin;
    /// Input points merged into an earlier point with exactly the same (x, y).
    std::size_t duplicateCount = 0;
};

/// Validates, deduplicates and shifts `points`.
///
/// Distinct points keep the order of their first occurrence in the input. The origin is a
/// rounded centre of the bounding box for which every subtraction is exact (checked point by
/// point); when no such origin exists (coordinates mixing magnitudes) it is (0, 0), which is
/// always exact. Either way the predicates see exactly the input geometry.
///
/// Throws InvalidInputError for a non-finite coordinate or elevation, for a shifted coordinate
/// outside the exact predicates' range (0 or 1e-60 .. 1e70 in magnitude), for more than
/// 2^32 - 5 points, and when fewer than three distinct points are not all collinear.
/// Complexity: O(n) expected (a hash table finds the duplicates); the passes around it run on
/// up to `threads` threads.
PreparedPoints preparePoints(std::span<const Point3> points, DuplicateZPolicy policy,
                             unsigned threads = 1);

} // namespace terratin

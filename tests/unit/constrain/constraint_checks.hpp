#pragma once
// The checks every constrained triangulation test makes, independent of the validator where
// they can be: chains of constrained edges joining each constraint's ends, vertices exactly on
// their segment, the input's vertices unchanged, the area of the input's convex hull.

#include "terratin/constrain/insert_constraints.hpp"

#include <cstdint>
#include <vector>

namespace terratin::test {

/// Asserts that `tin`, made by insertConstraints(original, constraints), passes
/// validateConstrainedDelaunay and the direct checks above.
void expectConstrainedDelaunay(const ConstrainedTin& tin, const TinMesh& original,
                               const ConstraintSet& constraints);

/// `count` segments between vertices drawn at random (a fixed generator, so the same seed
/// gives the same segments on every platform).
std::vector<std::array<std::uint32_t, 2>> randomSegments(std::size_t vertexCount, std::size_t count,
                                                         std::uint64_t seed);

/// Random walks of `steps` steps of about a fiftieth of the unit square's width, started in
/// it and clipped to `mesh`'s hull (TinLocator::clipToSurface), with the triangles found for
/// their points. A fixed generator: the same seed gives the same walks everywhere.
ConstraintSet walksWithTriangles(const TinMesh& mesh, int walks, int steps, std::uint64_t seed);

/// `lines` clipped to `mesh`'s hull (TinLocator::clipToSurface), with the triangles found for
/// their points.
ConstraintSet locatedPolylines(const TinMesh& mesh, const std::vector<std::vector<Point3>>& lines);

/// Whether `tin` has an edge a-b marked constrained on each of its half-edges.
bool hasConstrainedEdge(const ConstrainedTin& tin, std::uint32_t a, std::uint32_t b);

} // namespace terratin::test

#pragma once
/// @file
/// Constrained Delaunay triangulation: constraint segments inserted into a Delaunay TIN.

#include "terratin/constrain/constrained_tin.hpp"
#include "terratin/geometry/point.hpp"
#include "terratin/progress.hpp"
#include "terratin/triangulate/tin_mesh.hpp"

#include <array>
#include <cstdint>
#include <span>
#include <vector>

namespace terratin {

/// In ConstraintSet::polylineTriangles: the search for the point starts at the previous point's
/// vertex (for a polyline's first point, anywhere). The value of TinLocator::kUnlocated, so that
/// clipToSurface's triangles serve as they are.
inline constexpr std::uint32_t kFromPreviousPoint = 0xffffffffU;

/// The constraints to insert, in the mesh's planar units.
struct ConstraintSet {
    /// Segments between vertices of the mesh, as vertex indices (TinMesh::vertices).
    std::vector<std::array<std::uint32_t, 2>> segments;
    /// Polylines of points (x, y as the mesh's vertices, z the elevation the point gets when it
    /// becomes a new vertex). A closed ring repeats its first point at the end.
    std::vector<std::vector<Point3>> polylines;
    /// Optional, for speed: for each polyline, for each of its points, a triangle of the mesh
    /// as given (a TinMesh triangle index) that holds the point or lies near it, where the
    /// search for the point starts (TinLocator::clipToSurface finds them), or
    /// kFromPreviousPoint. Empty, or one list per polyline, as long as it. Any triangles give a
    /// constrained Delaunay TIN with the same vertices; the numbering of its triangles, and the
    /// diagonals of cocircular points, may depend on them.
    std::vector<std::vector<std::uint32_t>> polylineTriangles;
    /// With polylineTriangles and no index segments: the polylines go in on up to `threads`
    /// threads, in `zones` bands of x at once, then what those stop short of in as many bands
    /// of y (0: one band per 20,000 polyline points, a power of two, at most 16; 1: one after
    /// another). The TIN depends on the zones, not on the threads.
    unsigned threads = 1;
    unsigned zones = 0;
};

/// Inserts every constraint of `constraints` into `mesh`, a Delaunay triangulation (as
/// triangulate() makes it), and returns the constrained Delaunay triangulation.
///
/// Postconditions: every constraint segment is a chain of constrained edges; every unconstrained
/// interior edge passes the exact empty-circle test with the opposite vertex; the triangles
/// still cover the convex hull. Every orientation and in-circle decision is exact
/// (geometry/predicates.hpp).
/// - A vertex lying exactly on a segment (exact orient2d == 0, strictly between its ends)
///   splits it; overlapping, duplicate and collinear segments share their edges.
/// - A polyline point becomes a new vertex (sourceIndex kConstraintPointSource) unless a vertex
///   has exactly its x and y: then that vertex is used and keeps its elevation.
/// - Two segments that cross get a new vertex (sourceIndex kIntersectionSource) at their
///   intersection, computed in double along the segment inserted first (segments go in the
///   order given: `segments`, then each polyline's points and segments; with zones, what a
///   zone stopped short goes in after the zones' polylines), c + t (d - c), with its
///   z interpolated linearly along that segment. Rounding may leave the vertex off either segment
///   by about one unit in the last place of the coordinates: both segments then bend through it
///   and their halves are constrained as they are.
/// - Where a segment crosses a constrained edge and passes within 2^-50 times the largest
///   coordinate involved (about 4 ulps) of one of that edge's vertices, it goes through that
///   vertex instead (so segments through an earlier crossing reuse its vertex); such a chain
///   vertex may lie that far off the segment. A crossing within that distance of a vertex is
///   that vertex. Where crossings still crowd within a few ulps and the same crossing comes
///   back while one segment is inserted, the segment goes through the nearer end of the
///   crossed edge (docs/algorithms.md).
/// - Zero-length segments are ignored.
/// Throws InvalidInputError, naming the constraint, for a vertex index out of range, a
/// non-finite coordinate, polylineTriangles of the wrong shape or out of range, or a polyline
/// point outside the convex hull of the mesh (clipping to the hull is not supported), and for
/// more than 2^32 - 2 segments in all; `mesh` is consumed either way. std::logic_error only
/// means a broken internal invariant (a bug).
/// Complexity: an O(n) fill of the flags and of the vertex-to-triangle map; per segment the
/// degree of its first vertex plus O(k) flips for the k edges it crosses (O(k^2) at worst), per
/// crossing a point insertion, per polyline point a walk from its triangle in polylineTriangles,
/// else (or for kFromPreviousPoint) from the previous point (the first from a bucket grid, O(n)
/// once); a pass over the triangles, O(n) once, to complete the vertex-to-triangle map when a
/// segment starts at a vertex nothing before reached (index segments, polylines without triangles).
/// With zones, the polylines of each band of x go in on a thread of their own as far as they stay
/// inside it, what they stop short of in bands of y the same way, and the rest on one thread; the
/// slots the zones reserved and left unused are then filled with the last vertices and triangles
/// (O(slots)). docs/algorithms.md ("Constrained Delaunay", step 5) describes the method.
/// `progress` (when given) is called from this thread with the share of the segments in so far
/// and "inserting constraints": every 64 steps (a polyline point inserted, a piece of a segment
/// between two crossings inserted), and every 20 ms while the zones work on other threads.
/// When it returns false the insertion stops within those 64 steps (each zone's) and throws
/// Cancelled.
ConstrainedTin insertConstraints(TinMesh mesh, const ConstraintSet& constraints,
                                 const ProgressCallback& progress = {});

/// Inserts `points` into `tin` (a constrained Delaunay TIN as insertConstraints makes it) as new
/// vertices, point i with sourceIndex `sources[i]`, and restores the constrained Delaunay
/// property by flips that never flip a constrained edge: afterwards every constraint is still a
/// chain of constrained edges and every unconstrained interior edge passes the exact
/// empty-circle test. A point on a constrained edge splits it; both halves stay constrained and
/// the chains through that edge get the point. A point with exactly the x and y of a vertex is
/// skipped. Returns the number of points inserted. Throws InvalidInputError for a point not
/// finite, or sizes that differ (`tin` unchanged), or a point outside the convex hull (`tin`
/// then holds some of the others, constrained Delaunay). With `changedTriangles`, it is resized
/// to the new triangle count and holds 1 for every triangle whose corners changed or that is new
/// (the others are as they were), else 0. Per point a walk and its flips. The walk starts at
/// `near[i]` when given (a triangle index of `tin` before the call, near point i: where it was
/// located), else at the previous point's triangle: give the points in spatial order (row by
/// row, say) then. With `near` and thousands of points, they go in in bands of x on up to
/// `threads` threads (zoned_vertices.hpp); the bands depend on the points alone, so the result
/// is the same for any `threads`.
std::size_t insertVertices(ConstrainedTin& tin, std::span<const Point3> points,
                           std::span<const std::uint32_t> sources,
                           std::vector<std::uint8_t>* changedTriangles = nullptr,
                           std::span<const std::uint32_t> near = {}, unsigned threads = 1);

} // namespace terratin

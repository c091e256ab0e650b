// Lawson repair (DagTriangulator::repairAllEdges), the safety net that makes the circum-circle
// method exact after an override: starting from a triangulation built with no legalisation at
// all, repair alone must reach an exact Delaunay triangulation, hull included.

#include "dag_triangulator.hpp"

#include "mesh_invariants.hpp"
#include "point_distributions.hpp"
#include "terratin/triangulate/mesh_validation.hpp"
#include "terratin/triangulate/point_set.hpp"

#include <gtest/gtest.h>

namespace terratin {
namespace {

// Inserts every point by subdivision only, so the result is a valid but (almost surely)
// non-Delaunay triangulation; then repairs it, checking the edges on `threads` threads.
TinMesh triangulateByRepairOnly(const std::vector<Point3>& input, std::size_t& repairFlips,
                                std::size_t& illegalBeforeRepair, unsigned threads = 1) {
    const PreparedPoints prepared = preparePoints(input, DuplicateZPolicy::First);
    detail::DagTriangulator triangulator(prepared.local);
    detail::PendingEdges pending;
    for (detail::VertexId q = 0; q < prepared.local.size(); ++q) {
        if (q == triangulator.highestVertex())
            continue;
        const detail::NodeId leaf = triangulator.locate(q);
        const int edge = triangulator.edgeContaining(leaf, q);
        if (edge >= 0)
            triangulator.splitEdge(leaf, edge, q, pending);
        else
            triangulator.splitTriangle(leaf, q, pending);
        pending.clear(); // no legalisation
    }
    TinMesh before;
    triangulator.extract(before.triangles, before.neighbours);
    for (const std::uint32_t source : prepared.sourceIndex)
        before.vertices.push_back(input[source]);
    illegalBeforeRepair = validateDelaunay(before).nonDelaunayEdges;

    repairFlips = triangulator.repairAllEdges(threads);
    TinMesh mesh;
    triangulator.extract(mesh.triangles, mesh.neighbours);
    mesh.vertices = before.vertices;
    return mesh;
}

TEST(DagRepair, ReachesExactDelaunay_FromAnUnlegalisedTriangulation) {
    for (const test::Distribution distribution :
         {test::Distribution::Uniform, test::Distribution::Grid, test::Distribution::Arc}) {
        const std::vector<Point3> points = test::generatePoints(distribution, 3000, 21);
        std::size_t flips = 0;
        std::size_t illegalBefore = 0;
        const TinMesh mesh = triangulateByRepairOnly(points, flips, illegalBefore);
        EXPECT_GT(illegalBefore, 0U) << test::toString(distribution) << ": nothing to repair";
        EXPECT_GT(flips, 0U);
        test::expectExactDelaunayOf(mesh, points);
    }
}

TEST(DagRepair, ReachesExactDelaunay_WhenTheEdgesAreCheckedOnThreeThreads) {
    // Enough points that the history's nodes split into three blocks of the check.
    for (const test::Distribution distribution :
         {test::Distribution::Uniform, test::Distribution::Grid}) {
        const std::vector<Point3> points = test::generatePoints(distribution, 40000, 22);
        std::size_t flips = 0;
        std::size_t illegalBefore = 0;
        const TinMesh mesh = triangulateByRepairOnly(points, flips, illegalBefore, 3);
        EXPECT_GT(illegalBefore, 0U) << test::toString(distribution) << ": nothing to repair";
        test::expectExactDelaunayOf(mesh, points);
    }
}

TEST(DagRepair, ReachesExactDelaunay_ForCocircularAndCollinearInputs) {
    for (const std::vector<Point3>& points :
         {test::cocircularRings(1.0), test::collinearPlusOne(200)}) {
        std::size_t flips = 0;
        std::size_t illegalBefore = 0;
        test::expectExactDelaunayOf(triangulateByRepairOnly(points, flips, illegalBefore),
                                    points);
    }
}

} // namespace
} // namespace terratin

// Lawson repair (DagTriangulator::repairEdgesFrom), the safety net that makes the circum-circle
// method exact after an override: starting from a triangulation built with no legalisation at
// all, repair alone must reach an exact Delaunay triangulation, hull included; and the
// rendezvous where the method's workers meet for it (RepairRendezvous).

#include "dag_triangulator.hpp"
#include "repair_rendezvous.hpp"

#include "mesh_invariants.hpp"
#include "point_distributions.hpp"
#include "terratin/triangulate/mesh_validation.hpp"
#include "terratin/triangulate/point_set.hpp"

#include <gtest/gtest.h>

#include <memory>
#include <thread>

namespace terratin {
namespace {

// Inserts q into the leaf holding it by subdivision alone, leaving every edge unchecked.
void subdivideOnly(detail::DagTriangulator& triangulator, detail::VertexId q) {
    const detail::NodeId leaf = triangulator.locate(q);
    const int edge = triangulator.edgeContaining(leaf, q);
    detail::PendingEdges pending;
    if (edge >= 0)
        triangulator.splitEdge(leaf, edge, q, pending);
    else
        triangulator.splitTriangle(leaf, q, pending);
}

TinMesh extractMesh(detail::DagTriangulator& triangulator, const PreparedPoints& prepared,
                    const std::vector<Point3>& input) {
    TinMesh mesh;
    triangulator.extract(mesh.triangles, mesh.neighbours);
    for (const std::uint32_t source : prepared.sourceIndex)
        mesh.vertices.push_back(input[source]);
    return mesh;
}

// Inserts every point by subdivision only, so the result is a valid but (almost surely)
// non-Delaunay triangulation; then repairs it, checking the edges on `threads` threads.
TinMesh triangulateByRepairOnly(const std::vector<Point3>& input, std::size_t& repairFlips,
                                std::size_t& illegalBeforeRepair, unsigned threads = 1) {
    const PreparedPoints prepared = preparePoints(input, DuplicateZPolicy::First);
    detail::DagTriangulator triangulator(prepared.local);
    for (detail::VertexId q = 0; q < prepared.local.size(); ++q)
        if (q != triangulator.highestVertex())
            subdivideOnly(triangulator, q);
    illegalBeforeRepair =
        validateDelaunay(extractMesh(triangulator, prepared, input)).nonDelaunayEdges;
    repairFlips = triangulator.repairEdgesFrom(0, threads);
    return extractMesh(triangulator, prepared, input);
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
        test::expectExactDelaunayOf(triangulateByRepairOnly(points, flips, illegalBefore), points);
    }
}

// A triangulation that is Delaunay except on the leaves of its newer half: the first half of
// the points is inserted with legalisation, the rest by subdivision alone. `firstUnlegalised`
// receives the first node id of the second half.
struct HalfLegalised {
    PreparedPoints prepared;
    std::unique_ptr<detail::DagTriangulator> triangulator;
    detail::NodeId firstUnlegalised = 0;
};

HalfLegalised triangulateHalfLegalised(const std::vector<Point3>& input) {
    HalfLegalised result{preparePoints(input, DuplicateZPolicy::First), nullptr, 0};
    result.triangulator = std::make_unique<detail::DagTriangulator>(result.prepared.local);
    detail::DagTriangulator& triangulator = *result.triangulator;
    const auto count = static_cast<detail::VertexId>(result.prepared.local.size());
    for (detail::VertexId q = 0; q < count; ++q) {
        if (q == triangulator.highestVertex())
            continue;
        if (q == count / 2)
            result.firstUnlegalised = triangulator.lowestFutureNodeOfThisThread();
        if (q < count / 2)
            triangulator.insertAtLeaf(triangulator.locate(q), q);
        else
            subdivideOnly(triangulator, q);
    }
    return result;
}

TEST(DagRepair, ReachesExactDelaunay_FromTheNewestLeavesAlone) {
    // The illegal edges lie on leaves of the second half, some of them against older leaves:
    // checking the leaves from the first unlegalised node on must find them all.
    for (const test::Distribution distribution :
         {test::Distribution::Uniform, test::Distribution::Grid, test::Distribution::Arc}) {
        const std::vector<Point3> points = test::generatePoints(distribution, 4000, 23);
        HalfLegalised half = triangulateHalfLegalised(points);
        EXPECT_GT(half.firstUnlegalised, 0U);
        const std::size_t flips = half.triangulator->repairEdgesFrom(half.firstUnlegalised);
        EXPECT_GT(flips, 0U) << test::toString(distribution) << ": nothing to repair";
        test::expectExactDelaunayOf(extractMesh(*half.triangulator, half.prepared, points), points);
    }
}

TEST(RepairRendezvous, RepairsOnce_WhenEveryWorkerHasArrivedOrLeft) {
    const std::vector<Point3> points = test::generatePoints(test::Distribution::Uniform, 3000, 24);
    HalfLegalised half = triangulateHalfLegalised(points);
    detail::RepairRendezvous rendezvous(*half.triangulator, 3);
    rendezvous.arrive(); // nothing asked for: returns at once
    EXPECT_FALSE(rendezvous.requested());

    rendezvous.request(half.firstUnlegalised + 100);
    rendezvous.request(half.firstUnlegalised); // the lower request wins
    EXPECT_TRUE(rendezvous.requested());
    {
        std::jthread arriving([&rendezvous] { rendezvous.arrive(); });
        std::jthread leaving([&rendezvous] { rendezvous.leave(); });
        rendezvous.arrive();
    }
    EXPECT_FALSE(rendezvous.requested());
    EXPECT_EQ(rendezvous.repairs(), 1U);
    EXPECT_GT(rendezvous.flips(), 0U);
    test::expectExactDelaunayOf(extractMesh(*half.triangulator, half.prepared, points), points);
}

TEST(RepairRendezvous, Stop_ReleasesAWaitingWorkerWithoutARepair) {
    const std::vector<Point3> points = test::generatePoints(test::Distribution::Uniform, 500, 25);
    HalfLegalised half = triangulateHalfLegalised(points);
    detail::RepairRendezvous rendezvous(*half.triangulator, 2);
    rendezvous.request(half.firstUnlegalised);
    {
        std::jthread waiting([&rendezvous] { rendezvous.arrive(); });
        rendezvous.stop();
    }
    EXPECT_EQ(rendezvous.repairs(), 0U);
    rendezvous.arrive(); // after stop(): returns at once
}

} // namespace
} // namespace terratin

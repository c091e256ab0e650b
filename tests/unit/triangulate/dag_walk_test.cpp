// DagTriangulator::walk from any start: a leaf, an inner node (stale, as the parallel
// methods' walks often start from), or the root; it must end at a leaf containing the point.

#include "dag_triangulator.hpp"

#include "point_distributions.hpp"
#include "terratin/triangulate/point_set.hpp"

#include <gtest/gtest.h>

namespace terratin {
namespace {

using detail::DagNode;
using detail::DagTriangulator;
using detail::NodeId;
using detail::VertexId;

bool containsClosed(const DagTriangulator& triangulator, NodeId n, VertexId q) {
    const DagNode& node = triangulator.node(n);
    const auto& predicates = triangulator.predicates();
    return predicates.orient(node.v[0], node.v[1], q) >= 0 &&
           predicates.orient(node.v[1], node.v[2], q) >= 0 &&
           predicates.orient(node.v[2], node.v[0], q) >= 0;
}

class DagWalk : public ::testing::TestWithParam<test::Distribution> {};

TEST_P(DagWalk, EndsAtALeafContainingThePoint_FromLeavesInnerNodesAndTheRoot) {
    const PreparedPoints prepared =
        preparePoints(test::generatePoints(GetParam(), 4000, 11), DuplicateZPolicy::First);
    DagTriangulator triangulator(prepared.local);
    const auto count = static_cast<VertexId>(prepared.local.size());
    std::vector<VertexId> inserted;
    // Insert the first half; walk to each point of the second half from several starts.
    for (VertexId q = 0; q < count / 2; ++q) {
        if (q == triangulator.highestVertex())
            continue;
        triangulator.insertAtLeaf(triangulator.locate(q), q);
        inserted.push_back(q);
    }
    const auto nodes = static_cast<NodeId>(triangulator.nodeCount());
    std::size_t innerStarts = 0;
    for (VertexId q = count / 2; q < count; ++q) {
        if (q == triangulator.highestVertex())
            continue;
        for (const NodeId start :
             {NodeId{0}, static_cast<NodeId>(q * 7919U % nodes), triangulator.newestNode()}) {
            if (triangulator.node(start).v[0] == detail::kNoNode)
                continue; // an id reserved but never used: not a triangle
            innerStarts += triangulator.node(start).isLeaf() ? 0 : 1;
            const NodeId found = triangulator.walk(q, start);
            ASSERT_TRUE(triangulator.node(found).isLeaf());
            ASSERT_TRUE(containsClosed(triangulator, found, q)) << "point " << q;
        }
    }
    EXPECT_GT(innerStarts, count / 2); // the root, at least, is inner
}

INSTANTIATE_TEST_SUITE_P(Distributions, DagWalk,
                         ::testing::Values(test::Distribution::Uniform, test::Distribution::Grid,
                                           test::Distribution::Arc),
                         [](const auto& paramInfo) { return test::toString(paramInfo.param); });

} // namespace
} // namespace terratin

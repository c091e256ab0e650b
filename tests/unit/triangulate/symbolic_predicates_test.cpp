// The predicates over vertex ids, with the auxiliary triangle's symbolic vertices.

#include "symbolic_predicates.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace terratin {
namespace {

using detail::SymbolicPredicates;

class SymbolicPredicatesTest : public ::testing::Test {
protected:
    // 0 = (0, 0), 1 = (1, 0), 2 = (0, 1), 3 = (2, 0): 0, 1, 3 collinear.
    std::vector<Point2> m_points{{0, 0}, {1, 0}, {0, 1}, {2, 0}};
    SymbolicPredicates m_predicates{m_points};
};

TEST_F(SymbolicPredicatesTest, AuxiliaryTriangleContainsEveryPoint) {
    const auto farLeft = m_predicates.farLeft();
    const auto farRight = m_predicates.farRight();
    for (detail::VertexId q = 0; q < m_points.size(); ++q)
        EXPECT_EQ(m_predicates.orient(farLeft, farRight, q), 1);
    // (1, 0) is lower than (0, 1): it lies left of (0, 1) -> p-1 and right of (0, 1) -> p-2.
    EXPECT_EQ(m_predicates.orient(2, farRight, 1), -1);
    EXPECT_EQ(m_predicates.orient(2, farLeft, 1), 1);
}

TEST_F(SymbolicPredicatesTest, IncircleIsZero_WhenAVertexRepeats) {
    const auto farRight = m_predicates.farRight();
    const auto farLeft = m_predicates.farLeft();
    EXPECT_EQ(m_predicates.incircle(0, 1, 2, 2), 0);
    EXPECT_EQ(m_predicates.incircle(2, farRight, 1, 2), 0);
    EXPECT_EQ(m_predicates.incircle(0, farRight, farLeft, 0), 0);
}

TEST_F(SymbolicPredicatesTest, IncircleAgreesWithFlipRule_ForSymbolicEdges) {
    const auto farRight = m_predicates.farRight();
    int compared = 0;
    // shouldFlip(i, j, k, l) is incircle(i, j, k, l) > 0 by definition: both formulations of
    // the limit must agree wherever both apply, i.e. for triangles (i, j, k) and (j, i, l)
    // that are both counter-clockwise.
    for (detail::VertexId j = 0; j < m_points.size(); ++j)
        for (detail::VertexId k = 0; k < m_points.size(); ++k)
            for (detail::VertexId l = 0; l < m_points.size(); ++l) {
                if (j == k || k == l || j == l || m_predicates.orient(farRight, j, k) <= 0 ||
                    m_predicates.orient(j, farRight, l) <= 0)
                    continue;
                EXPECT_EQ(m_predicates.shouldFlip(farRight, j, k, l),
                          m_predicates.incircle(farRight, j, k, l) > 0)
                    << j << " " << k << " " << l;
                ++compared;
            }
    EXPECT_GT(compared, 0);
}

} // namespace
} // namespace terratin

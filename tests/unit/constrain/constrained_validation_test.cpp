#include "terratin/constrain/constrained_validation.hpp"

#include "terratin/constrain/insert_constraints.hpp"

#include <gtest/gtest.h>

namespace terratin {
namespace {

// The unit square with one more point near corner 3, split along 0-2 with 0-2 constrained:
// 0-2 is then not locally Delaunay (3 lies inside the circle through 0, 1, 2)... except that
// it is constrained.
ConstrainedTin squareWithConstrainedDiagonal() {
    ConstrainedTin tin;
    tin.mesh.vertices = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0.2, 0.9, 0}};
    tin.mesh.sourceIndex = {0, 1, 2, 3};
    tin.mesh.triangles = {0, 1, 2, 0, 2, 3};
    tin.mesh.neighbours = {-1, -1, 1, 0, -1, -1};
    tin.constrained = {0, 0, 1, 1, 0, 0};
    tin.chains = {{0, 2}};
    return tin;
}

TEST(ValidateConstrainedDelaunay, AcceptsConstrainedNonDelaunayEdge) {
    const ConstrainedValidation validation =
        validateConstrainedDelaunay(squareWithConstrainedDiagonal());
    EXPECT_TRUE(validation.ok());
}

TEST(ValidateConstrainedDelaunay, DetectsNonDelaunayEdge_WhenNotConstrained) {
    ConstrainedTin tin = squareWithConstrainedDiagonal();
    tin.constrained = {0, 0, 0, 0, 0, 0};
    tin.chains.clear();
    const ConstrainedValidation validation = validateConstrainedDelaunay(tin);
    EXPECT_EQ(validation.nonDelaunayEdges, 2U); // seen from both sides
    EXPECT_FALSE(validation.ok());
}

TEST(ValidateConstrainedDelaunay, DetectsMissingChainEdge_WhenNothingIsMarked) {
    ConstrainedTin tin = squareWithConstrainedDiagonal();
    tin.constrained = {0, 0, 0, 0, 0, 0};
    const ConstrainedValidation validation = validateConstrainedDelaunay(tin);
    EXPECT_EQ(validation.missingChainEdges, 1U);
    EXPECT_FALSE(validation.ok());
}

TEST(ValidateConstrainedDelaunay, DetectsConstrainedEdgeFlippedByHand) {
    ConstrainedTin tin = squareWithConstrainedDiagonal();
    // The other diagonal, 1-3: triangles (0, 1, 3) and (1, 2, 3), the flags kept on it.
    tin.mesh.triangles = {0, 1, 3, 1, 2, 3};
    tin.mesh.neighbours = {-1, 1, -1, -1, -1, 0};
    tin.constrained = {0, 1, 0, 0, 0, 1};
    const ConstrainedValidation validation = validateConstrainedDelaunay(tin);
    EXPECT_EQ(validation.missingChainEdges, 1U);     // 0-2 is gone
    EXPECT_EQ(validation.strayConstrainedEdges, 1U); // 1-3 is on no chain
    EXPECT_FALSE(validation.ok());
}

TEST(ValidateConstrainedDelaunay, DetectsFlagOnOneSideOnly) {
    ConstrainedTin tin = squareWithConstrainedDiagonal();
    tin.constrained[3] = 0;
    EXPECT_EQ(validateConstrainedDelaunay(tin).asymmetricFlags, 1U);
}

TEST(ValidateConstrainedDelaunay, DetectsAreaBelowTheHull) {
    ConstrainedTin tin = squareWithConstrainedDiagonal();
    tin.mesh.vertices[3] = {2, 3, 0}; // both triangles stay counter-clockwise; the hull grows
    const ConstrainedValidation validation = validateConstrainedDelaunay(tin);
    EXPECT_FALSE(validation.areaMatchesHull);
    EXPECT_FALSE(validation.ok());
}

TEST(ValidateConstrainedDelaunay, DetectsWrongFlagArraySize) {
    ConstrainedTin tin = squareWithConstrainedDiagonal();
    tin.constrained.pop_back();
    EXPECT_GT(validateConstrainedDelaunay(tin).badIndices, 0U);
}

TEST(ValidateConstrainedDelaunay, DetectsClockwiseTriangle) {
    ConstrainedTin tin = squareWithConstrainedDiagonal();
    std::swap(tin.mesh.triangles[1], tin.mesh.triangles[2]);
    EXPECT_GT(validateConstrainedDelaunay(tin).notCounterClockwise, 0U);
}

// The validator on insertConstraints' own output for the same square: the diagonal made
// constrained by inserting it.
TEST(ValidateConstrainedDelaunay, AcceptsInsertedConstraint_AndItsChainMatters) {
    TinMesh mesh;
    mesh.vertices = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0.2, 0.9, 0}};
    mesh.sourceIndex = {0, 1, 2, 3};
    mesh.triangles = {0, 1, 3, 1, 2, 3}; // Delaunay: diagonal 1-3
    mesh.neighbours = {-1, 1, -1, -1, -1, 0};
    ConstraintSet constraints;
    constraints.segments = {{0, 2}};
    ConstrainedTin tin = insertConstraints(mesh, constraints);
    EXPECT_TRUE(validateConstrainedDelaunay(tin).ok());
    tin.chains.clear(); // the constrained edge is now on no chain
    EXPECT_EQ(validateConstrainedDelaunay(tin).strayConstrainedEdges, 1U);
}

} // namespace
} // namespace terratin

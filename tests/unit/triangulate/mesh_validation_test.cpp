#include "terratin/triangulate/mesh_validation.hpp"

#include <gtest/gtest.h>

namespace terratin {
namespace {

// Unit square split along the diagonal 0-2, with a point 4 just outside edge 1-2 making the
// square's triangulation choice matter.
TinMesh squareMesh() {
    TinMesh mesh;
    mesh.vertices = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
    mesh.triangles = {0, 1, 2, 0, 2, 3};
    // Triangle 0 edges: 0-1 hull, 1-2 hull, 2-0 shared with triangle 1 (its edge 0-2).
    mesh.neighbours = {-1, -1, 1, 0, -1, -1};
    return mesh;
}

TEST(ValidateDelaunay, AcceptsValidSquare) {
    const MeshValidation validation = validateDelaunay(squareMesh());
    EXPECT_TRUE(validation.ok());
    EXPECT_TRUE(validation.eulerHolds);
}

TEST(ValidateDelaunay, DetectsClockwiseTriangle) {
    TinMesh mesh = squareMesh();
    std::swap(mesh.triangles[1], mesh.triangles[2]);
    EXPECT_GT(validateDelaunay(mesh).notCounterClockwise, 0U);
}

TEST(ValidateDelaunay, DetectsAsymmetricNeighbours) {
    TinMesh mesh = squareMesh();
    mesh.neighbours[3] = -1;
    EXPECT_FALSE(validateDelaunay(mesh).ok());
    EXPECT_GT(validateDelaunay(mesh).asymmetricNeighbours, 0U);
}

TEST(ValidateDelaunay, DetectsNonDelaunayEdge) {
    TinMesh mesh = squareMesh();
    mesh.vertices[3] = {0.2, 0.9, 0}; // now 3 lies inside the circle through 0, 1, 2
    const MeshValidation validation = validateDelaunay(mesh);
    EXPECT_EQ(validation.nonDelaunayEdges, 2U); // seen from both sides
    EXPECT_FALSE(validation.ok());
}

TEST(ValidateDelaunay, DetectsConcaveBoundary) {
    TinMesh mesh = squareMesh();
    mesh.vertices[3] = {2, 3, 0}; // both triangles stay counter-clockwise; the boundary turns
                                  // right at vertex 2
    EXPECT_GT(validateDelaunay(mesh).boundaryProblems, 0U);
}

TEST(ValidateDelaunay, DetectsUnusedVertex) {
    TinMesh mesh = squareMesh();
    mesh.vertices.push_back({5, 5, 0});
    const MeshValidation validation = validateDelaunay(mesh);
    EXPECT_EQ(validation.unusedVertices, 1U);
    EXPECT_FALSE(validation.eulerHolds);
}

TEST(ValidateDelaunay, DetectsIndexOutOfRange) {
    TinMesh mesh = squareMesh();
    mesh.triangles[0] = 17;
    EXPECT_GT(validateDelaunay(mesh).badIndices, 0U);
}

} // namespace
} // namespace terratin

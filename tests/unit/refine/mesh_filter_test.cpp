// Removing triangles from a TIN: compaction, neighbour links across removed triangles, vertices
// only removed triangles used, and the long-edge filter for point clouds.

#include "terratin/error.hpp"
#include "terratin/triangulate/mesh_filter.hpp"
#include "terratin/triangulate/triangulate.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace terratin {
namespace {

// A 5 x 5 lattice of unit spacing plus one far point that makes long thin triangles.
TinMesh latticeWithOutlier() {
    std::vector<Point3> points;
    for (int y = 0; y < 5; ++y)
        for (int x = 0; x < 5; ++x)
            points.push_back({static_cast<double>(x), static_cast<double>(y), 1.0 * x});
    points.push_back({20.0, 2.5, 0.0});
    TriangulationOptions options;
    options.threads = 1;
    return triangulate(points, options).mesh;
}

void expectConsistentLinks(const TinMesh& mesh) {
    for (std::size_t t = 0; t < mesh.triangleCount(); ++t) {
        for (int i = 0; i < 3; ++i) {
            const std::int32_t n = mesh.neighbours[3 * t + i];
            if (n == kNoNeighbour)
                continue;
            ASSERT_LT(static_cast<std::size_t>(n), mesh.triangleCount());
            // The neighbour has the same edge, reversed, and links back.
            const std::uint32_t a = mesh.triangles[3 * t + i];
            const std::uint32_t b = mesh.triangles[3 * t + (i + 1) % 3];
            bool found = false;
            for (int j = 0; j < 3; ++j) {
                const auto u = static_cast<std::size_t>(n);
                if (mesh.triangles[3 * u + j] == b && mesh.triangles[3 * u + (j + 1) % 3] == a) {
                    found = true;
                    EXPECT_EQ(mesh.neighbours[3 * u + j], static_cast<std::int32_t>(t));
                }
            }
            EXPECT_TRUE(found);
        }
    }
}

TEST(MeshFilter, LongEdgesDropped_AndTheOutlierRemoved) {
    TinMesh mesh = latticeWithOutlier();
    const std::size_t before = mesh.triangleCount();
    ASSERT_EQ(mesh.vertexCount(), 26U);
    const std::size_t dropped = dropLongEdgeTriangles(mesh, 2.0);
    EXPECT_GT(dropped, 0U);
    EXPECT_EQ(mesh.triangleCount(), before - dropped);
    EXPECT_EQ(mesh.triangleCount(), 32U); // the lattice's 4 x 4 squares, two triangles each
    EXPECT_EQ(mesh.vertexCount(), 25U);   // the far point only had long edges
    EXPECT_EQ(mesh.sourceIndex.size(), 25U);
    for (const Point3& v : mesh.vertices)
        EXPECT_LE(v.x, 4.0);
    expectConsistentLinks(mesh);
    std::size_t boundary = 0;
    for (const std::int32_t n : mesh.neighbours)
        boundary += n == kNoNeighbour ? 1U : 0U;
    EXPECT_EQ(boundary, 16U);
}

TEST(MeshFilter, DropTrianglesKeepsOrderAndLinksAcrossKeptOnes) {
    TinMesh mesh = latticeWithOutlier();
    const TinMesh original = mesh;
    std::vector<std::uint8_t> drop(mesh.triangleCount(), 0);
    drop[0] = 1;
    drop[drop.size() / 2] = 1;
    EXPECT_EQ(dropTriangles(mesh, drop), 2U);
    EXPECT_EQ(mesh.triangleCount(), original.triangleCount() - 2);
    expectConsistentLinks(mesh);
    EXPECT_EQ(mesh.vertices[mesh.triangles[0]], original.vertices[original.triangles[3]]);
}

TEST(MeshFilter, NothingDropped_WhenEveryEdgeIsShort) {
    TinMesh mesh = latticeWithOutlier();
    EXPECT_EQ(dropLongEdgeTriangles(mesh, 100.0), 0U);
    EXPECT_EQ(mesh.vertexCount(), 26U);
    EXPECT_THROW(dropLongEdgeTriangles(mesh, 0.0), InvalidInputError);
    EXPECT_THROW(dropLongEdgeTriangles(mesh, std::nan("")), InvalidInputError);
}

} // namespace
} // namespace terratin

// The refiner's in-place triangulation on its own: lattice points (every 2 x 2 block
// cocircular, many points on the hull's edges) and random points stay exactly Delaunay, each
// insertion reports the triangles around the new point, and edited triangles change version.

#include "refine_mesh.hpp"

#include "terratin/triangulate/mesh_validation.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>
#include <vector>

namespace terratin::detail {
namespace {

TinMesh toTinMesh(const RefineMesh& mesh, const std::vector<Point2>& points, std::size_t used) {
    TinMesh tin;
    mesh.extract(tin.triangles, tin.neighbours);
    for (std::size_t v = 0; v < used; ++v) {
        tin.vertices.push_back({points[v].x, points[v].y, 0.0});
        tin.sourceIndex.push_back(static_cast<std::uint32_t>(v));
    }
    return tin;
}

/// Inserts points[hullSize..) in order, checking each insertion's fan and growth.
void insertAll(RefineMesh& mesh, const std::vector<Point2>& points, std::size_t hullSize) {
    RefineMesh::Scratch scratch;
    std::vector<TriId> fan;
    std::size_t triangles = hullSize - 2;
    TriId start = 0;
    for (auto p = static_cast<VertexId>(hullSize); p < points.size(); ++p) {
        const TriId holder = mesh.walk(p, start);
        const std::uint32_t before = mesh.version(holder);
        fan.clear();
        triangles += static_cast<std::size_t>(mesh.insert(p, holder, scratch, fan));
        EXPECT_NE(mesh.version(holder), before);
        // The fan is every triangle with p as a corner, each once.
        std::vector<TriId> around;
        for (TriId t = 0; t < mesh.slotCount(); ++t)
            if (mesh.inUse(t)) {
                const auto& v = mesh.triangle(t).v;
                if (std::find(v.begin(), v.end(), p) != v.end())
                    around.push_back(t);
            }
        std::vector<TriId> sortedFan = fan;
        std::sort(sortedFan.begin(), sortedFan.end());
        ASSERT_EQ(sortedFan, around) << "point " << p;
        start = fan.front();
    }
    std::size_t inUse = 0;
    for (TriId t = 0; t < mesh.slotCount(); ++t)
        inUse += mesh.inUse(t) ? 1U : 0U;
    EXPECT_EQ(inUse, triangles);
}

TEST(RefineMesh, LatticeStaysExactlyDelaunay_WithCocircularBlocksAndHullEdgePoints) {
    constexpr int kSide = 24;
    std::vector<Point2> points{{0, 0}, {kSide - 1, 0}, {kSide - 1, kSide - 1}, {0, kSide - 1}};
    std::vector<Point2> inner;
    for (int y = 0; y < kSide; ++y)
        for (int x = 0; x < kSide; ++x)
            if (!((x == 0 || x == kSide - 1) && (y == 0 || y == kSide - 1)))
                inner.push_back({0.5 * x + 1e6, 0.5 * y - 3e6}); // large offsets, exact halves
    for (Point2& corner : points)
        corner = {0.5 * corner.x + 1e6, 0.5 * corner.y - 3e6};
    std::shuffle(inner.begin(), inner.end(), std::mt19937(4));
    points.insert(points.end(), inner.begin(), inner.end());

    RefineMesh mesh(points, 2 * points.size(), 1);
    const std::vector<VertexId> hull{0, 1, 2, 3};
    mesh.startFromHull(hull);
    insertAll(mesh, points, hull.size());
    const TinMesh tin = toTinMesh(mesh, points, points.size());
    const MeshValidation validation = validateDelaunay(tin);
    EXPECT_TRUE(validation.ok()) << (validation.problems.empty() ? "" : validation.problems[0]);
    EXPECT_EQ(tin.triangleCount(), 2U * (kSide - 1) * (kSide - 1));
}

TEST(RefineMesh, RandomPointsInAConvexPolygonStayExactlyDelaunay) {
    // A regular 12-gon (cocircular: its fan needs flips to become Delaunay) and points inside.
    std::vector<Point2> points;
    for (int k = 0; k < 12; ++k) {
        const double angle = 2.0 * 3.141592653589793 * k / 12.0;
        points.push_back({100.0 * std::cos(angle), 100.0 * std::sin(angle)});
    }
    std::mt19937 random(8);
    std::uniform_real_distribution<double> coordinate(-60.0, 60.0);
    for (int i = 0; i < 3000; ++i)
        points.push_back({coordinate(random), coordinate(random)});
    RefineMesh mesh(points, 2 * points.size(), 1);
    std::vector<VertexId> hull(12);
    std::iota(hull.begin(), hull.end(), VertexId{0});
    mesh.startFromHull(hull);
    EXPECT_TRUE(validateDelaunay(toTinMesh(mesh, points, 12)).ok());
    insertAll(mesh, points, hull.size());
    EXPECT_TRUE(validateDelaunay(toTinMesh(mesh, points, points.size())).ok());
}

} // namespace
} // namespace terratin::detail

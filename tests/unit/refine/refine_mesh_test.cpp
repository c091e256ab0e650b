// The refiner's in-place triangulation on its own: lattice points (every 2 x 2 block
// cocircular, many points on the hull's edges) and random points stay exactly Delaunay, each
// insertion reports the triangles around the new point, edited triangles change version, and
// an insertion restricted to a strip touches nothing outside it.

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

/// Every vertex in strip 0: no restriction ever applies.
std::vector<std::uint8_t> oneStrip(const std::vector<Point2>& points) {
    return std::vector<std::uint8_t>(points.size(), 0);
}

/// Inserts points[hullSize..) in order, checking each insertion's fan and growth.
void insertAll(RefineMesh& mesh, unsigned region, const std::vector<Point2>& points,
               std::size_t hullSize) {
    RefineMesh::InsertScratch scratch;
    std::size_t triangles = hullSize - 2;
    TriId start = mesh.slotsInUse().front();
    for (auto p = static_cast<VertexId>(hullSize); p < points.size(); ++p) {
        const TriId holder = mesh.walk(points[p], start);
        const std::uint32_t before = mesh.version(holder);
        const int added = mesh.tryInsert(p, start, StripRange::all(), region, scratch);
        ASSERT_TRUE(added == 1 || added == 2) << "point " << p;
        triangles += static_cast<std::size_t>(added);
        EXPECT_NE(mesh.version(holder), before);
        // The fan is every triangle with p as a corner, each once.
        std::vector<TriId> around;
        for (const TriId t : mesh.slotsInUse()) {
            const auto& v = mesh.triangle(t).v;
            if (std::find(v.begin(), v.end(), p) != v.end())
                around.push_back(t);
        }
        std::vector<TriId> sortedFan = scratch.fan;
        std::sort(sortedFan.begin(), sortedFan.end());
        ASSERT_EQ(sortedFan, around) << "point " << p;
        start = scratch.fan.front();
    }
    EXPECT_EQ(mesh.slotsInUse().size(), triangles);
}

std::vector<RefineVertex> verticesOf(const std::vector<Point2>& points,
                                     const std::vector<std::uint8_t>& strips) {
    std::vector<RefineVertex> vertices;
    for (std::size_t v = 0; v < points.size(); ++v)
        vertices.push_back({points[v], 0, 0, 0.0F, strips[v]});
    return vertices;
}

/// A mesh over `points` with its hull and one region for the rest.
struct TestMesh {
    TestMesh(const std::vector<Point2>& points, const std::vector<std::uint8_t>& strips,
             const std::vector<VertexId>& hull)
        : vertices(verticesOf(points, strips)), mesh(vertices, 2 * points.size()) {
        const unsigned hullRegion = mesh.addRegion(hull.size());
        region = mesh.addRegion(2 * points.size() - hull.size());
        mesh.startFromHull(hull, hullRegion);
    }
    std::vector<RefineVertex> vertices;
    RefineMesh mesh;
    unsigned region = 0;
};

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

    const std::vector<VertexId> hull{0, 1, 2, 3};
    TestMesh test(points, oneStrip(points), hull);
    insertAll(test.mesh, test.region, points, hull.size());
    const TinMesh tin = toTinMesh(test.mesh, points, points.size());
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
    std::vector<VertexId> hull(12);
    std::iota(hull.begin(), hull.end(), VertexId{0});
    TestMesh test(points, oneStrip(points), hull);
    EXPECT_TRUE(validateDelaunay(toTinMesh(test.mesh, points, 12)).ok());
    insertAll(test.mesh, test.region, points, hull.size());
    EXPECT_TRUE(validateDelaunay(toTinMesh(test.mesh, points, points.size())).ok());
}

TEST(RefineMesh, RestrictedInsertionStaysInItsStripOrChangesNothing) {
    // A square cut at x = 50 into strip 0 (x < 50) and strip 1. The hull's triangles span
    // both: the first 300 random points go in without restriction, the others restricted to
    // their side's strip, and the refused ones afterwards without restriction.
    std::vector<Point2> points{{0, 0}, {100, 0}, {100, 100}, {0, 100}};
    std::mt19937 random(21);
    std::uniform_real_distribution<double> coordinate(1.0, 99.0);
    for (int i = 0; i < 2000; ++i)
        points.push_back({coordinate(random), coordinate(random)});
    std::vector<std::uint8_t> strips(points.size());
    for (std::size_t v = 0; v < points.size(); ++v)
        strips[v] = points[v].x < 50.0 ? 0 : 1;
    TestMesh test(points, strips, {0, 1, 2, 3});
    const auto own = [&](VertexId p) { return StripRange{strips[p], strips[p]}; };
    RefineMesh& mesh = test.mesh;
    RefineMesh::InsertScratch scratch;
    for (auto p = VertexId{4}; p < 304; ++p)
        ASSERT_GT(
            mesh.tryInsert(p, mesh.slotsInUse().front(), StripRange::all(), test.region, scratch),
            0);
    std::vector<VertexId> refused;
    std::size_t inserted = 0;
    for (auto p = VertexId{304}; p < points.size(); ++p) {
        const std::vector<TriId> slots = mesh.slotsInUse();
        // Start from a triangle of p's strip, if any.
        const auto start = std::find_if(slots.begin(), slots.end(),
                                        [&](TriId t) { return mesh.strips(t) == own(p); });
        if (start == slots.end()) {
            refused.push_back(p);
            continue;
        }
        std::vector<MeshTriangle> before;
        for (const TriId t : slots)
            before.push_back(mesh.triangle(t));
        if (mesh.tryInsert(p, *start, own(p), test.region, scratch) == 0) {
            // It met a triangle spanning both strips, and nothing changed.
            EXPECT_EQ(scratch.needed, (StripRange{0, 1}));
            ASSERT_EQ(mesh.slotsInUse(), slots);
            for (std::size_t k = 0; k < slots.size(); ++k) {
                EXPECT_EQ(mesh.triangle(slots[k]).v, before[k].v);
                EXPECT_EQ(mesh.triangle(slots[k]).n, before[k].n);
                EXPECT_EQ(mesh.version(slots[k]), before[k].version);
            }
            refused.push_back(p);
            continue;
        }
        ++inserted;
        // The new triangles belong to the strip; the ones of the other strip are untouched.
        for (const TriId t : scratch.fan)
            EXPECT_EQ(mesh.strips(t), own(p));
        for (std::size_t k = 0; k < slots.size(); ++k)
            if (!(before[k].strips == own(p)) && before[k].strips.single()) {
                EXPECT_EQ(mesh.triangle(slots[k]).v, before[k].v);
                EXPECT_EQ(mesh.triangle(slots[k]).n, before[k].n);
            }
    }
    // Most insertions stay within their strip; the refused ones complete the triangulation.
    EXPECT_GT(inserted, 1300U);
    EXPECT_FALSE(refused.empty());
    for (const VertexId p : refused)
        ASSERT_GT(
            mesh.tryInsert(p, mesh.slotsInUse().front(), StripRange::all(), test.region, scratch),
            0);
    const TinMesh tin = toTinMesh(mesh, points, points.size());
    EXPECT_EQ(tin.triangleCount(), 2 * points.size() - 2 - 4);
    EXPECT_TRUE(validateDelaunay(tin).ok());
}

} // namespace
} // namespace terratin::detail

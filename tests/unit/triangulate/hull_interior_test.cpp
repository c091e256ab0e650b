// HullInterior: the boxes inside a TIN's convex hull that spare breakline points a walk. Every
// point a box holds must be inside the hull by the exact test, on hulls with many corners, with
// collinear vertices (grids) and far from the origin; and where the hull is not one convex
// cycle there are no boxes.

#include "hull_interior.hpp"
#include "terratin/triangulate/tin_locator.hpp"
#include "terratin/triangulate/triangulate.hpp"

#include "point_distributions.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

namespace terratin {
namespace {

using detail::HullInterior;

std::vector<std::array<std::uint32_t, 2>> hullEdges(const TinMesh& mesh) {
    std::vector<std::array<std::uint32_t, 2>> edges;
    for (std::size_t t = 0; t < mesh.triangleCount(); ++t)
        for (std::size_t i = 0; i < 3; ++i)
            if (mesh.neighbours[3 * t + i] == kNoNeighbour)
                edges.push_back({mesh.triangles[3 * t + i], mesh.triangles[3 * t + (i + 1) % 3]});
    return edges;
}

struct Box {
    Point2 low;
    Point2 high;
};

Box boundsOf(const TinMesh& mesh) {
    Box box{{mesh.vertices[0].x, mesh.vertices[0].y}, {mesh.vertices[0].x, mesh.vertices[0].y}};
    for (const Point3& p : mesh.vertices) {
        box.low = {std::min(box.low.x, p.x), std::min(box.low.y, p.y)};
        box.high = {std::max(box.high.x, p.x), std::max(box.high.y, p.y)};
    }
    return box;
}

HullInterior interiorOf(const TinMesh& mesh, std::size_t rows) {
    const Box box = boundsOf(mesh);
    return HullInterior(mesh.vertices, hullEdges(mesh), box.low,
                        (box.high.y - box.low.y) / static_cast<double>(rows - 1), rows);
}

// Counts the points HullInterior holds among random points over the mesh's box and a margin
// round it, on its boxes' edges too, and checks each by the exact walk; returns the count and
// how many of them the walk finds inside.
std::pair<std::size_t, std::size_t>
checkHeldPointsInside(const TinMesh& mesh, const HullInterior& interior, unsigned seed) {
    const Box box = boundsOf(mesh);
    const double w = box.high.x - box.low.x;
    const double h = box.high.y - box.low.y;
    std::mt19937_64 random(seed);
    std::uniform_real_distribution<double> u(-0.05, 1.05);
    TinLocator locator(mesh);
    std::size_t held = 0;
    std::size_t inside = 0;
    for (int i = 0; i < 20000; ++i) {
        Point2 p{box.low.x + u(random) * w, box.low.y + u(random) * h};
        if (i % 4 == 1) // on a vertex's x: boxes end exactly on the hull's corners
            p.x = mesh.vertices[static_cast<std::size_t>(i) % mesh.vertexCount()].x;
        if (i % 4 == 2)
            p.y = mesh.vertices[static_cast<std::size_t>(i) % mesh.vertexCount()].y;
        const bool found = locator.locate(p).has_value();
        inside += found ? 1 : 0;
        if (interior.holds(p)) {
            ++held;
            EXPECT_TRUE(found) << p.x << " " << p.y;
        }
    }
    return {held, inside};
}

TEST(HullInterior, EveryPointItHoldsIsInsideByTheExactTest_OnThePapersDistributions) {
    for (const test::Distribution distribution :
         {test::Distribution::Uniform, test::Distribution::Gauss, test::Distribution::Cluster,
          test::Distribution::Grid}) {
        SCOPED_TRACE(test::toString(distribution));
        const TinMesh mesh = triangulate(test::generatePoints(distribution, 5000, 3)).mesh;
        const auto [held, inside] = checkHeldPointsInside(mesh, interiorOf(mesh, 40), 5);
        EXPECT_GT(held, inside / 2); // the boxes cover most of the hull
    }
}

TEST(HullInterior, EveryPointItHoldsIsInsideByTheExactTest_OnAGridFarFromTheOrigin) {
    // A grid's hull has hundreds of collinear vertices; at 1e6 the coordinates' last bits
    // matter. The rows run past the hull's top, as TinLocator's do.
    std::vector<Point3> points;
    for (int row = 0; row < 60; ++row)
        for (int col = 0; col < 80; ++col)
            points.push_back({1e6 + 0.1 * col, 2e6 + 0.1 * row, 0.0});
    const TinMesh mesh = triangulate(points).mesh;
    const Box box = boundsOf(mesh);
    const HullInterior interior(mesh.vertices, hullEdges(mesh), box.low, 0.37, 17);
    const auto [held, inside] = checkHeldPointsInside(mesh, interior, 6);
    EXPECT_GT(held, inside * 9 / 10); // a rectangle: nearly all of it
}

// Two unit squares apart, each of two triangles: the hull edges form two cycles.
TinMesh twoSquares() {
    TinMesh mesh;
    for (const double x0 : {0.0, 3.0})
        for (const Point2 p : {Point2{0, 0}, Point2{1, 0}, Point2{1, 1}, Point2{0, 1}})
            mesh.vertices.push_back({x0 + p.x, p.y, 0.0});
    for (std::uint32_t base : {0U, 4U}) {
        for (const std::uint32_t v : {0U, 1U, 2U, 0U, 2U, 3U})
            mesh.triangles.push_back(base + v);
        const auto first = static_cast<std::int32_t>(base / 2);
        for (const std::int32_t n :
             {kNoNeighbour, kNoNeighbour, first + 1, first, kNoNeighbour, kNoNeighbour})
            mesh.neighbours.push_back(n);
    }
    mesh.sourceIndex.resize(mesh.vertices.size(), 0);
    return mesh;
}

TEST(HullInterior, HoldsNothing_WhereTheHullIsNotOneConvexCycle) {
    const TinMesh squares = twoSquares();
    const HullInterior apart(squares.vertices, hullEdges(squares), {0.0, 0.0}, 0.25, 5);
    EXPECT_FALSE(apart.holds({0.5, 0.5}));
    EXPECT_FALSE(apart.holds({3.5, 0.5}));

    // An L: a grid's triangles with their centre in the top right quarter left out.
    TinMesh grid = triangulate(test::generatePoints(test::Distribution::Grid, 400, 1)).mesh;
    TinMesh ell;
    ell.vertices = grid.vertices;
    ell.sourceIndex = grid.sourceIndex;
    std::vector<std::int32_t> renumber(grid.triangleCount(), kNoNeighbour);
    for (std::size_t t = 0; t < grid.triangleCount(); ++t) {
        double cx = 0.0;
        double cy = 0.0;
        for (std::size_t i = 0; i < 3; ++i) {
            cx += grid.vertices[grid.triangles[3 * t + i]].x / 3.0;
            cy += grid.vertices[grid.triangles[3 * t + i]].y / 3.0;
        }
        if (cx > 0.5 && cy > 0.5)
            continue;
        renumber[t] = static_cast<std::int32_t>(ell.triangleCount());
        for (std::size_t i = 0; i < 3; ++i)
            ell.triangles.push_back(grid.triangles[3 * t + i]);
    }
    for (std::size_t t = 0; t < grid.triangleCount(); ++t)
        if (renumber[t] != kNoNeighbour)
            for (std::size_t i = 0; i < 3; ++i) {
                const std::int32_t n = grid.neighbours[3 * t + i];
                ell.neighbours.push_back(n == kNoNeighbour ? kNoNeighbour
                                                           : renumber[static_cast<std::size_t>(n)]);
            }
    const Box box = boundsOf(ell);
    const HullInterior notConvex(ell.vertices, hullEdges(ell), box.low, 0.1, 11);
    for (double x = 0.05; x < 1.0; x += 0.1)
        for (double y = 0.05; y < 1.0; y += 0.1)
            EXPECT_FALSE(notConvex.holds({x, y})) << x << " " << y;
}

} // namespace
} // namespace terratin

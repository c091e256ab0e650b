#include "constraint_checks.hpp"

#include "mesh_invariants.hpp"
#include "terratin/constrain/constrained_validation.hpp"
#include "terratin/geometry/predicates.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

namespace terratin::test {

namespace {

Point2 planar(const Point3& p) {
    return {p.x, p.y};
}

bool between(double a, double b, double x) {
    return std::min(a, b) <= x && x <= std::max(a, b);
}

// Every vertex of a segment's chain that is not a crossing lies exactly on the segment.
void expectOnSegment(const ConstrainedTin& tin, const std::vector<std::uint32_t>& chain,
                     const Point3& a, const Point3& b, std::size_t k) {
    for (const std::uint32_t v : chain) {
        if (tin.mesh.sourceIndex[v] == kIntersectionSource)
            continue;
        const Point3& p = tin.mesh.vertices[v];
        EXPECT_EQ(predicates::orient2d(planar(a), planar(b), planar(p)), 0.0)
            << "constraint " << k << ": vertex " << v << " is off its segment";
        EXPECT_TRUE(between(a.x, b.x, p.x) && between(a.y, b.y, p.y))
            << "constraint " << k << ": vertex " << v << " is beyond its segment";
    }
}

void expectChainOfEdges(const ConstrainedTin& tin, const std::vector<std::uint32_t>& chain,
                        std::size_t k) {
    for (std::size_t j = 1; j < chain.size(); ++j)
        EXPECT_TRUE(hasConstrainedEdge(tin, chain[j - 1], chain[j]))
            << "constraint " << k << ": " << chain[j - 1] << "-" << chain[j]
            << " is not a constrained edge";
}

void expectSegmentChains(const ConstrainedTin& tin, const ConstraintSet& constraints) {
    for (std::size_t k = 0; k < constraints.segments.size(); ++k) {
        const std::vector<std::uint32_t>& chain = tin.chains[k];
        const auto [a, b] = constraints.segments[k];
        ASSERT_FALSE(chain.empty());
        EXPECT_EQ(chain.front(), a);
        EXPECT_EQ(chain.back(), b);
        expectChainOfEdges(tin, chain, k);
        expectOnSegment(tin, chain, tin.mesh.vertices[a], tin.mesh.vertices[b], k);
    }
}

// A polyline's chain passes, in order, through vertices at each of its points' x and y.
void expectPolylineChains(const ConstrainedTin& tin, const ConstraintSet& constraints) {
    for (std::size_t p = 0; p < constraints.polylines.size(); ++p) {
        const std::size_t k = constraints.segments.size() + p;
        const std::vector<std::uint32_t>& chain = tin.chains[k];
        expectChainOfEdges(tin, chain, k);
        std::size_t position = 0;
        for (const Point3& point : constraints.polylines[p]) {
            while (position < chain.size() &&
                   planar(tin.mesh.vertices[chain[position]]) != planar(point))
                ++position;
            ASSERT_LT(position, chain.size()) << "polyline " << p << " point (" << point.x << ", "
                                              << point.y << ") is not on its chain in order";
        }
    }
}

} // namespace

bool hasConstrainedEdge(const ConstrainedTin& tin, std::uint32_t a, std::uint32_t b) {
    std::size_t marked = 0;
    std::size_t found = 0;
    for (std::size_t h = 0; h < tin.mesh.triangles.size(); ++h) {
        const std::uint32_t from = tin.mesh.triangles[h];
        const std::uint32_t to = tin.mesh.triangles[h % 3 == 2 ? h - 2 : h + 1];
        if ((from == a && to == b) || (from == b && to == a)) {
            ++found;
            marked += tin.constrained[h];
        }
    }
    return found > 0 && marked == found;
}

void expectConstrainedDelaunay(const ConstrainedTin& tin, const TinMesh& original,
                               const ConstraintSet& constraints) {
    const ConstrainedValidation validation = validateConstrainedDelaunay(tin);
    EXPECT_TRUE(validation.ok()) << [&] {
        std::string all;
        for (const std::string& problem : validation.problems)
            all += problem + "\n";
        return all;
    }();

    ASSERT_GE(tin.mesh.vertexCount(), original.vertexCount());
    EXPECT_EQ(tin.mesh.vertexCount(), original.vertexCount() + tin.addedPoints + tin.intersections);
    for (std::size_t v = 0; v < original.vertexCount(); ++v) {
        ASSERT_EQ(tin.mesh.vertices[v], original.vertices[v]);
        ASSERT_EQ(tin.mesh.sourceIndex[v], original.sourceIndex[v]);
    }
    std::size_t added = 0;
    for (std::size_t v = original.vertexCount(); v < tin.mesh.vertexCount(); ++v)
        added += tin.mesh.sourceIndex[v] == kConstraintPointSource ? 1U : 0U;
    EXPECT_EQ(added, tin.addedPoints);

    // Constraints inside the hull leave the hull, and so its area, as it was.
    const std::vector<Point3> vertices(original.vertices.begin(), original.vertices.end());
    const double hullArea = convexHullArea(vertices);
    EXPECT_NEAR(triangleAreaSum(tin.mesh), hullArea, 1e-9 * hullArea);

    ASSERT_EQ(tin.chains.size(), constraints.segments.size() + constraints.polylines.size());
    expectSegmentChains(tin, constraints);
    expectPolylineChains(tin, constraints);
}

std::vector<std::array<std::uint32_t, 2>> randomSegments(std::size_t vertexCount, std::size_t count,
                                                         std::uint64_t seed) {
    std::uint64_t state = seed;
    // splitmix64
    const auto next = [&state] {
        state += 0x9e3779b97f4a7c15ULL;
        std::uint64_t z = state;
        z = (z ^ (z >> 30U)) * 0xbf58476d1ce4e5b9ULL;
        z = (z ^ (z >> 27U)) * 0x94d049bb133111ebULL;
        return z ^ (z >> 31U);
    };
    std::vector<std::array<std::uint32_t, 2>> segments;
    for (std::size_t k = 0; k < count; ++k)
        segments.push_back({static_cast<std::uint32_t>(next() % vertexCount),
                            static_cast<std::uint32_t>(next() % vertexCount)});
    return segments;
}

} // namespace terratin::test

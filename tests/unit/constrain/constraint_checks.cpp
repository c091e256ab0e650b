#include "constraint_checks.hpp"

#include "mesh_invariants.hpp"
#include "terratin/constrain/constrained_validation.hpp"
#include "terratin/geometry/predicates.hpp"
#include "terratin/triangulate/tin_locator.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <unordered_map>

namespace terratin::test {

namespace {

Point2 planar(const Point3& p) {
    return {p.x, p.y};
}

bool between(double a, double b, double x) {
    return std::min(a, b) <= x && x <= std::max(a, b);
}

// Every vertex of a segment's chain that is not a crossing lies on the segment: exactly, or
// within the documented 4 ulps of the coordinates when the segment met a constrained edge of
// that vertex there.
void expectOnSegment(const ConstrainedTin& tin, const std::vector<std::uint32_t>& chain,
                     const Point3& a, const Point3& b, std::size_t k) {
    const double length = std::hypot(b.x - a.x, b.y - a.y);
    if (length == 0.0) {
        EXPECT_EQ(chain.size(), 1U) << "constraint " << k << " has zero length";
        return;
    }
    for (const std::uint32_t v : chain) {
        if (tin.mesh.sourceIndex[v] == kIntersectionSource)
            continue;
        const Point3& p = tin.mesh.vertices[v];
        const double magnitude = std::max({std::fabs(a.x), std::fabs(a.y), std::fabs(b.x),
                                           std::fabs(b.y), std::fabs(p.x), std::fabs(p.y)});
        const double snap = 4 * std::numeric_limits<double>::epsilon() * magnitude;
        EXPECT_LE(std::fabs(predicates::orient2d(planar(a), planar(b), planar(p))) / length, snap)
            << "constraint " << k << ": vertex " << v << " is off its segment";
        EXPECT_TRUE(between(a.x, b.x, p.x) && between(a.y, b.y, p.y))
            << "constraint " << k << ": vertex " << v << " is beyond its segment";
    }
}

std::uint64_t edgeKey(std::uint32_t a, std::uint32_t b) {
    return a < b ? (std::uint64_t{a} << 32U) | b : (std::uint64_t{b} << 32U) | a;
}

// For each edge, its half-edges and how many of them are marked constrained.
struct EdgeMarks {
    std::size_t halfEdges = 0;
    std::size_t marked = 0;
};

std::unordered_map<std::uint64_t, EdgeMarks> edgeMarks(const ConstrainedTin& tin) {
    std::unordered_map<std::uint64_t, EdgeMarks> marks;
    for (std::size_t h = 0; h < tin.mesh.triangles.size(); ++h) {
        EdgeMarks& edge =
            marks[edgeKey(tin.mesh.triangles[h], tin.mesh.triangles[h % 3 == 2 ? h - 2 : h + 1])];
        ++edge.halfEdges;
        edge.marked += tin.constrained[h] != 0 ? 1U : 0U;
    }
    return marks;
}

using Marks = std::unordered_map<std::uint64_t, EdgeMarks>;

void expectChainOfEdges(const Marks& marks, const std::vector<std::uint32_t>& chain,
                        std::size_t k) {
    for (std::size_t j = 1; j < chain.size(); ++j)
        EXPECT_TRUE([&] {
            const auto found = marks.find(edgeKey(chain[j - 1], chain[j]));
            return found != marks.end() && found->second.marked == found->second.halfEdges;
        }()) << "constraint "
             << k << ": " << chain[j - 1] << "-" << chain[j] << " is not a constrained edge";
}

void expectSegmentChains(const ConstrainedTin& tin, const ConstraintSet& constraints,
                         const Marks& marks) {
    for (std::size_t k = 0; k < constraints.segments.size(); ++k) {
        const std::vector<std::uint32_t>& chain = tin.chains[k];
        const auto [a, b] = constraints.segments[k];
        ASSERT_FALSE(chain.empty());
        EXPECT_EQ(chain.front(), a);
        EXPECT_EQ(chain.back(), b);
        expectChainOfEdges(marks, chain, k);
        expectOnSegment(tin, chain, tin.mesh.vertices[a], tin.mesh.vertices[b], k);
    }
}

// A polyline's chain passes, in order, through vertices at each of its points' x and y.
void expectPolylineChains(const ConstrainedTin& tin, const ConstraintSet& constraints,
                          const Marks& marks) {
    for (std::size_t p = 0; p < constraints.polylines.size(); ++p) {
        const std::size_t k = constraints.segments.size() + p;
        const std::vector<std::uint32_t>& chain = tin.chains[k];
        expectChainOfEdges(marks, chain, k);
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
    const Marks marks = edgeMarks(tin);
    expectSegmentChains(tin, constraints, marks);
    expectPolylineChains(tin, constraints, marks);
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

ConstraintSet walksWithTriangles(const TinMesh& mesh, int walks, int steps, std::uint64_t seed) {
    std::vector<std::vector<Point3>> lines;
    std::mt19937_64 random(seed);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    for (int k = 0; k < walks; ++k) {
        std::vector<Point3> line{{unit(random), unit(random), 1.0}};
        double heading = 6.283 * unit(random);
        for (int j = 0; j < steps; ++j) {
            heading += unit(random) - 0.5;
            line.push_back({line.back().x + 0.02 * std::cos(heading),
                            line.back().y + 0.02 * std::sin(heading), 1.0});
        }
        lines.push_back(line);
    }
    return locatedPolylines(mesh, lines);
}

ConstraintSet locatedPolylines(const TinMesh& mesh, const std::vector<std::vector<Point3>>& lines) {
    ConstraintSet constraints;
    for (std::vector<TinLocator::LocatedPolyline>& parts : TinLocator(mesh).clipToSurface(lines, 2))
        for (TinLocator::LocatedPolyline& part : parts) {
            constraints.polylines.push_back(std::move(part.points));
            constraints.polylineTriangles.push_back(std::move(part.triangles));
        }
    return constraints;
}

} // namespace terratin::test

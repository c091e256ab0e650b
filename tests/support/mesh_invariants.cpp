#include "mesh_invariants.hpp"

#include "terratin/geometry/predicates.hpp"
#include "terratin/triangulate/mesh_validation.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <set>
#include <utility>
#include <vector>

namespace terratin::test {

namespace {
Point2 planar(const Point3& p) {
    return {p.x, p.y};
}

double twiceSignedArea(const Point2& a, const Point2& b, const Point2& c) {
    return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
}
/// Interior edges whose quadrilateral incircleTieBroken would flip: none in the one Delaunay
/// triangulation every method builds (ties included). Counted from each side.
std::size_t tieBrokenIllegalEdges(const TinMesh& mesh) {
    std::size_t illegal = 0;
    for (std::size_t t = 0; t < mesh.triangleCount(); ++t) {
        const std::uint32_t* corner = &mesh.triangles[3 * t];
        for (std::size_t i = 0; i < 3; ++i) {
            const std::int32_t n = mesh.neighbours[3 * t + i];
            if (n < 0)
                continue;
            // The corner of n that is not on the shared edge corner[i] -> corner[i + 1].
            const std::uint32_t* other = &mesh.triangles[3 * static_cast<std::size_t>(n)];
            std::uint32_t opposite = other[0];
            for (std::size_t j = 0; j < 3; ++j)
                if (other[j] != corner[i] && other[j] != corner[(i + 1) % 3])
                    opposite = other[j];
            auto xy = [&](std::uint32_t v) {
                return Point2{mesh.vertices[v].x, mesh.vertices[v].y};
            };
            if (predicates::incircleTieBroken(xy(corner[0]), xy(corner[1]), xy(corner[2]),
                                              xy(opposite)) > 0)
                ++illegal;
        }
    }
    return illegal;
}
} // namespace

double convexHullArea(std::span<const Point3> points) {
    std::vector<Point2> sorted;
    sorted.reserve(points.size());
    for (const Point3& p : points)
        sorted.push_back(planar(p));
    std::sort(sorted.begin(), sorted.end(),
              [](const Point2& a, const Point2& b) { return a.x != b.x ? a.x < b.x : a.y < b.y; });
    sorted.erase(std::unique(sorted.begin(), sorted.end()), sorted.end());
    if (sorted.size() < 3)
        return 0.0;
    std::vector<Point2> hull(2 * sorted.size());
    std::size_t k = 0;
    for (const Point2& p : sorted) {
        while (k >= 2 && predicates::orient2d(hull[k - 2], hull[k - 1], p) <= 0.0)
            --k;
        hull[k++] = p;
    }
    const std::size_t lowerSize = k + 1;
    for (auto it = sorted.rbegin() + 1; it != sorted.rend(); ++it) {
        while (k >= lowerSize && predicates::orient2d(hull[k - 2], hull[k - 1], *it) <= 0.0)
            --k;
        hull[k++] = *it;
    }
    hull.resize(k - 1);
    double twiceArea = 0.0;
    for (std::size_t i = 1; i + 1 < hull.size(); ++i)
        twiceArea += twiceSignedArea(hull[0], hull[i], hull[i + 1]);
    return twiceArea / 2.0;
}

double triangleAreaSum(const TinMesh& mesh) {
    double twiceArea = 0.0;
    for (std::size_t t = 0; t < mesh.triangleCount(); ++t)
        twiceArea += twiceSignedArea(planar(mesh.vertices[mesh.triangles[3 * t]]),
                                     planar(mesh.vertices[mesh.triangles[3 * t + 1]]),
                                     planar(mesh.vertices[mesh.triangles[3 * t + 2]]));
    return twiceArea / 2.0;
}

void expectExactDelaunayOf(const TinMesh& mesh, std::span<const Point3> input) {
    const MeshValidation validation = validateDelaunay(mesh);
    EXPECT_TRUE(validation.ok()) << [&] {
        std::string all;
        for (const std::string& problem : validation.problems)
            all += problem + "\n";
        return all;
    }();
    EXPECT_EQ(validation.nonDelaunayEdges, 0U);
    EXPECT_EQ(tieBrokenIllegalEdges(mesh), 0U)
        << "cocircular points not split as predicates::incircleTieBroken decides";
    EXPECT_EQ(validation.asymmetricNeighbours, 0U);
    EXPECT_EQ(validation.notCounterClockwise, 0U);
    EXPECT_TRUE(validation.eulerHolds);

    std::set<std::pair<double, double>> distinctInput;
    for (const Point3& p : input)
        distinctInput.emplace(p.x, p.y);
    std::set<std::pair<double, double>> vertices;
    for (const Point3& v : mesh.vertices)
        vertices.emplace(v.x, v.y);
    EXPECT_EQ(vertices.size(), mesh.vertices.size()) << "a vertex appears twice";
    EXPECT_TRUE(vertices == distinctInput) << "vertices differ from the distinct input points";

    // Both sums carry rounding errors of at most about n * 2^-52 relative (n terms, each
    // product rounded); 1e-9 relative is far above that for the sizes tested and far below
    // the area of any missing or overlapping triangle.
    const double hullArea = convexHullArea(input);
    const double meshArea = triangleAreaSum(mesh);
    EXPECT_NEAR(meshArea, hullArea, 1e-9 * hullArea) << "triangles do not cover the convex hull";
}

std::vector<CornerTriple> sortedTriangles(std::span<const Point3> vertices,
                                          std::span<const std::uint32_t> triangles) {
    std::vector<CornerTriple> sorted;
    sorted.reserve(triangles.size() / 3);
    for (std::size_t t = 0; t < triangles.size(); t += 3) {
        CornerTriple corners{};
        for (std::size_t i = 0; i < 3; ++i) {
            const Point3& p = vertices[triangles[t + i]];
            corners[i] = {p.x, p.y};
        }
        std::sort(corners.begin(), corners.end());
        sorted.push_back(corners);
    }
    std::sort(sorted.begin(), sorted.end());
    return sorted;
}

void expectSameTriangles(const TinMesh& a, const TinMesh& b) {
    const std::vector<CornerTriple> first = sortedTriangles(a.vertices, a.triangles);
    const std::vector<CornerTriple> second = sortedTriangles(b.vertices, b.triangles);
    ASSERT_EQ(first.size(), second.size());
    const auto mismatch = std::mismatch(first.begin(), first.end(), second.begin());
    EXPECT_TRUE(mismatch.first == first.end())
        << "triangles differ from the one with corner (" << (*mismatch.first)[0].first << ", "
        << (*mismatch.first)[0].second << ") on, sorted";
}

} // namespace terratin::test

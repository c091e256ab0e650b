#include "conforming_tin.hpp"

#include "terratin/geometry/predicates.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <map>
#include <utility>

namespace terratin::test {

EdgeCount expectConforming(const TinMesh& mesh) {
    std::map<std::pair<std::uint32_t, std::uint32_t>, std::size_t> directed;
    for (std::size_t t = 0; t < mesh.triangleCount(); ++t) {
        const std::uint32_t* v = &mesh.triangles[3 * t];
        EXPECT_GT(predicates::orient2d(xy(mesh.vertices[v[0]]), xy(mesh.vertices[v[1]]),
                                       xy(mesh.vertices[v[2]])),
                  0.0)
            << "triangle " << t << " is not counter-clockwise";
        for (std::size_t e = 0; e < 3; ++e) {
            const bool added = directed.emplace(std::pair{v[e], v[(e + 1) % 3]}, t).second;
            EXPECT_TRUE(added) << "two triangles on one side of edge " << v[e] << "-"
                               << v[(e + 1) % 3];
        }
    }
    EdgeCount count;
    for (const auto& [edge, t] : directed) {
        const auto twin = directed.find({edge.second, edge.first});
        const std::size_t e = static_cast<std::size_t>(
            std::find(&mesh.triangles[3 * t], &mesh.triangles[3 * t + 3], edge.first) -
            &mesh.triangles[3 * t]);
        const std::int32_t neighbour = mesh.neighbours[3 * t + e];
        if (twin == directed.end()) {
            EXPECT_EQ(neighbour, kNoNeighbour) << "triangle " << t << " names a neighbour it lacks";
            ++count.boundary;
        } else {
            EXPECT_EQ(neighbour, static_cast<std::int32_t>(twin->second))
                << "triangles " << t << " and " << twin->second << " share an edge unlinked";
            ++count.interior;
        }
    }
    count.interior /= 2;
    return count;
}

double areaSum(const TinMesh& mesh) {
    double area = 0.0;
    for (std::size_t t = 0; t < mesh.triangleCount(); ++t) {
        const Point3& a = mesh.vertices[mesh.triangles[3 * t]];
        const Point3& b = mesh.vertices[mesh.triangles[3 * t + 1]];
        const Point3& c = mesh.vertices[mesh.triangles[3 * t + 2]];
        area += 0.5 * ((b.x - a.x) * (c.y - a.y) - (c.x - a.x) * (b.y - a.y));
    }
    return area;
}

} // namespace terratin::test

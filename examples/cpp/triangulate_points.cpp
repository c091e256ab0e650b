// Triangulates a handful of points with terratin::core and prints the triangles.

#include "terratin/error.hpp"
#include "terratin/triangulate/triangulate.hpp"
#include "terratin/version.hpp"

#include <cstddef>
#include <cstdio>
#include <vector>

int main() {
    // x, y in any planar units, z carried along: a 10 x 10 square and two points inside it.
    const std::vector<terratin::Point3> points = {
        {0.0, 0.0, 100.0},  {10.0, 0.0, 102.0}, {10.0, 10.0, 105.0},
        {0.0, 10.0, 101.0}, {3.0, 4.0, 110.0},  {7.0, 6.0, 108.0},
    };
    try {
        // Default options: a fixed seed, the fastest method, every hardware thread.
        const terratin::TriangulationResult result = terratin::triangulate(points);
        const terratin::TinMesh& mesh = result.mesh;

        // n points with h on the convex hull make 2n - h - 2 triangles: here 2 * 6 - 4 - 2 = 6.
        std::printf("terratin %s: %zu points, %zu triangles\n", terratin::version(),
                    mesh.vertexCount(), mesh.triangleCount());
        // Flat arrays: triangle t is vertices triangles[3t], [3t+1], [3t+2], counter-clockwise.
        for (std::size_t t = 0; t < mesh.triangleCount(); ++t)
            std::printf("  triangle %zu: vertices %u %u %u\n", t, mesh.triangles[3 * t],
                        mesh.triangles[3 * t + 1], mesh.triangles[3 * t + 2]);
    } catch (const terratin::Error& error) {
        std::fprintf(stderr, "triangulate_points: %s\n", error.what());
        return 1;
    }
    return 0;
}

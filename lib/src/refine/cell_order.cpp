#include "cell_order.hpp"

#include "../triangulate/parallel_for.hpp"

#include <algorithm>
#include <array>
#include <cstdint>
#include <numeric>
#include <vector>

namespace terratin::detail {

namespace {

/// Indices 0..n-1 sorted by `keys` (stable), by two 16-bit counting-sort passes.
std::vector<std::uint32_t> orderOfKeys(const std::vector<std::uint32_t>& keys) {
    std::vector<std::uint32_t> order(keys.size());
    std::iota(order.begin(), order.end(), 0U);
    std::vector<std::uint32_t> scratch(keys.size());
    for (const unsigned shift : {0U, 16U}) {
        std::vector<std::size_t> start((std::size_t{1} << 16U) + 1, 0);
        for (const std::uint32_t key : keys)
            ++start[((key >> shift) & 0xFFFFU) + 1];
        std::partial_sum(start.begin(), start.end(), start.begin());
        for (const std::uint32_t i : order)
            scratch[start[(keys[i] >> shift) & 0xFFFFU]++] = i;
        order.swap(scratch);
    }
    return order;
}

} // namespace

void orderByCell(TinMesh& mesh, unsigned threads) {
    const std::size_t vertexCount = mesh.vertexCount();
    const std::size_t triangleCount = mesh.triangleCount();

    // Vertices by cell.
    const std::vector<std::uint32_t> vertexOrder = orderOfKeys(mesh.sourceIndex);
    std::vector<std::uint32_t> newVertex(vertexCount);
    {
        std::vector<Point3> vertices(vertexCount);
        std::vector<std::uint32_t> sourceIndex(vertexCount);
        parallelFor(vertexCount, threads, [&](unsigned, std::size_t begin, std::size_t end) {
            for (std::size_t rank = begin; rank < end; ++rank) {
                const std::uint32_t old = vertexOrder[rank];
                newVertex[old] = static_cast<std::uint32_t>(rank);
                vertices[rank] = mesh.vertices[old];
                sourceIndex[rank] = mesh.sourceIndex[old];
            }
        });
        mesh.vertices.swap(vertices);
        mesh.sourceIndex.swap(sourceIndex);
    }

    // Triangles by their lowest corner (counting sort: one bucket per vertex).
    std::vector<std::uint32_t> lowest(triangleCount);
    parallelFor(triangleCount, threads, [&](unsigned, std::size_t begin, std::size_t end) {
        for (std::size_t t = begin; t < end; ++t) {
            std::uint32_t* corners = &mesh.triangles[3 * t];
            for (std::size_t k = 0; k < 3; ++k)
                corners[k] = newVertex[corners[k]];
            lowest[t] = std::min({corners[0], corners[1], corners[2]});
        }
    });
    std::vector<std::uint32_t> start(vertexCount + 1, 0);
    for (const std::uint32_t corner : lowest)
        ++start[corner + 1];
    std::partial_sum(start.begin(), start.end(), start.begin());
    std::vector<std::int32_t> newTriangle(triangleCount);
    for (std::size_t t = 0; t < triangleCount; ++t)
        newTriangle[t] = static_cast<std::int32_t>(start[lowest[t]]++);
    std::vector<std::uint32_t> triangles(mesh.triangles.size());
    std::vector<std::int32_t> neighbours(mesh.neighbours.size());
    parallelFor(triangleCount, threads, [&](unsigned, std::size_t begin, std::size_t end) {
        for (std::size_t t = begin; t < end; ++t) {
            const auto to = static_cast<std::size_t>(newTriangle[t]);
            for (std::size_t k = 0; k < 3; ++k) {
                triangles[3 * to + k] = mesh.triangles[3 * t + k];
                const std::int32_t neighbour = mesh.neighbours[3 * t + k];
                neighbours[3 * to + k] = neighbour == kNoNeighbour
                                             ? kNoNeighbour
                                             : newTriangle[static_cast<std::size_t>(neighbour)];
            }
        }
    });
    mesh.triangles.swap(triangles);
    mesh.neighbours.swap(neighbours);
}

} // namespace terratin::detail

#include "cell_order.hpp"

#include "../parallel/parallel_for.hpp"

#include <algorithm>
#include <array>
#include <cstdint>
#include <memory>
#include <numeric>
#include <vector>

namespace terratin::detail {

namespace {

/// Indices 0..n-1 sorted by `keys` (stable), by counting-sort passes over 11-bit digits, as
/// many as the largest key needs: 2048 buckets stay in the first-level cache.
std::vector<std::uint32_t> orderOfKeys(const std::vector<std::uint32_t>& keys) {
    constexpr unsigned kDigitBits = 11;
    constexpr std::uint32_t kBuckets = 1U << kDigitBits;
    const std::uint32_t largest = keys.empty() ? 0 : *std::max_element(keys.begin(), keys.end());
    std::vector<std::uint32_t> order(keys.size());
    std::iota(order.begin(), order.end(), 0U);
    std::vector<std::uint32_t> scratch(keys.size());
    for (unsigned shift = 0; shift < 32 && (shift == 0 || (largest >> shift) != 0);
         shift += kDigitBits) {
        std::array<std::uint32_t, kBuckets + 1> start{};
        for (const std::uint32_t key : keys)
            ++start[((key >> shift) & (kBuckets - 1)) + 1];
        std::partial_sum(start.begin(), start.end(), start.begin());
        for (const std::uint32_t i : order)
            scratch[start[(keys[i] >> shift) & (kBuckets - 1)]++] = i;
        order.swap(scratch);
    }
    return order;
}

} // namespace

TinMesh extractInCellOrder(const RefineMesh& mesh, std::span<const RefineVertex> vertices,
                           std::span<const VertexRange> ranges, std::int64_t width,
                           unsigned threads, std::vector<TriId>* slotOfTriangle,
                           std::size_t spareVertices) {
    // The vertices in use, one range after the other, and their cells.
    std::size_t vertexCount = 0;
    for (const VertexRange& range : ranges)
        vertexCount += range.end - range.first;
    std::vector<VertexId> ids(vertexCount);
    std::vector<std::uint32_t> cells(vertexCount);
    std::size_t next = 0;
    for (const VertexRange& range : ranges) {
        const std::size_t first = next;
        parallelFor(
            range.end - range.first, threads, [&](unsigned, std::size_t begin, std::size_t end) {
                for (std::size_t k = begin; k < end; ++k) {
                    const RefineVertex& vertex = vertices[range.first + k];
                    ids[first + k] = static_cast<VertexId>(range.first + k);
                    cells[first + k] = static_cast<std::uint32_t>(vertex.row * width + vertex.col);
                }
            });
        next += range.end - range.first;
    }

    // Vertices by cell. A vertex id's rank is kept in an array over all ids, unset but for
    // the ids in use: their pages only are touched.
    const std::vector<std::uint32_t> byCell = orderOfKeys(cells);
    VertexId idEnd = 0;
    for (const VertexRange& range : ranges)
        idEnd = std::max(idEnd, range.end);
    const std::unique_ptr<std::uint32_t[]> rankOf(new std::uint32_t[idEnd]);
    TinMesh out;
    reserveRoom(out, vertexCount, spareVertices);
    out.vertices.resize(vertexCount);
    out.sourceIndex.resize(vertexCount);
    parallelFor(vertexCount, threads, [&](unsigned, std::size_t begin, std::size_t end) {
        for (std::size_t rank = begin; rank < end; ++rank) {
            const std::uint32_t k = byCell[rank];
            const RefineVertex& vertex = vertices[ids[k]];
            rankOf[ids[k]] = static_cast<std::uint32_t>(rank);
            out.vertices[rank] = {vertex.position.x, vertex.position.y,
                                  static_cast<double>(vertex.z)};
            out.sourceIndex[rank] = cells[k];
        }
    });

    // Triangles by their lowest corner (counting sort: one bucket per vertex), in slot order
    // within a bucket.
    const std::vector<TriId> slots = mesh.slotsInUse();
    const std::size_t triangleCount = slots.size();
    std::vector<std::uint32_t> lowest(triangleCount);
    parallelFor(triangleCount, threads, [&](unsigned, std::size_t begin, std::size_t end) {
        for (std::size_t k = begin; k < end; ++k) {
            const MeshTriangle& triangle = mesh.triangle(slots[k]);
            lowest[k] =
                std::min({rankOf[triangle.v[0]], rankOf[triangle.v[1]], rankOf[triangle.v[2]]});
        }
    });
    std::vector<std::uint32_t> start(vertexCount + 1, 0);
    for (const std::uint32_t corner : lowest)
        ++start[corner + 1];
    std::partial_sum(start.begin(), start.end(), start.begin());
    // The final index of each slot in use, in an array over all slots (unset elsewhere).
    const std::unique_ptr<std::int32_t[]> indexOf(new std::int32_t[mesh.slotEnd()]);
    std::vector<std::uint32_t> position(triangleCount);
    for (std::size_t k = 0; k < triangleCount; ++k) {
        position[k] = start[lowest[k]]++;
        indexOf[slots[k]] = static_cast<std::int32_t>(position[k]);
    }
    if (slotOfTriangle != nullptr) {
        slotOfTriangle->resize(triangleCount);
        for (std::size_t k = 0; k < triangleCount; ++k)
            (*slotOfTriangle)[position[k]] = slots[k];
    }
    out.triangles.resize(3 * triangleCount);
    out.neighbours.resize(3 * triangleCount);
    parallelFor(triangleCount, threads, [&](unsigned, std::size_t begin, std::size_t end) {
        for (std::size_t k = begin; k < end; ++k) {
            const MeshTriangle& triangle = mesh.triangle(slots[k]);
            const std::size_t to = position[k];
            // TinMesh: neighbours[3t+i] across the edge from corner i to corner i+1, which is
            // the edge opposite corner i+2 here.
            for (std::size_t i = 0; i < 3; ++i) {
                out.triangles[3 * to + i] = rankOf[triangle.v[i]];
                const TriId across = triangle.n[(i + 2) % 3];
                out.neighbours[3 * to + i] = across == kNoTriangle ? kNoNeighbour : indexOf[across];
            }
        }
    });
    return out;
}

} // namespace terratin::detail

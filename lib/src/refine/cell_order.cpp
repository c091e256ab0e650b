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

/// The vertices in use, one range after the other: their ids, and the cell of each.
struct UsedVertices {
    std::vector<VertexId> ids;
    std::vector<std::uint32_t> cells;
};

UsedVertices usedVertices(std::span<const RefineVertex> vertices,
                          std::span<const VertexRange> ranges, std::int64_t width,
                          unsigned threads) {
    std::size_t vertexCount = 0;
    for (const VertexRange& range : ranges)
        vertexCount += range.end - range.first;
    UsedVertices used{std::vector<VertexId>(vertexCount), std::vector<std::uint32_t>(vertexCount)};
    std::size_t next = 0;
    for (const VertexRange& range : ranges) {
        const std::size_t first = next;
        parallelFor(range.end - range.first, threads,
                    [&](unsigned, std::size_t begin, std::size_t end) {
                        for (std::size_t k = begin; k < end; ++k) {
                            const RefineVertex& vertex = vertices[range.first + k];
                            used.ids[first + k] = static_cast<VertexId>(range.first + k);
                            used.cells[first + k] =
                                static_cast<std::uint32_t>(vertex.row * width + vertex.col);
                        }
                    });
        next += range.end - range.first;
    }
    return used;
}

/// `out`'s vertices and sourceIndex in the order `byCell` gives the used vertices, and each
/// one's rank in rankOf[id] (only the ids in use are written: their pages only are touched).
void placeVertices(const UsedVertices& used, std::span<const RefineVertex> vertices,
                   const std::vector<std::uint32_t>& byCell, std::uint32_t* rankOf, TinMesh& out,
                   unsigned threads) {
    out.vertices.resize(used.ids.size());
    out.sourceIndex.resize(used.ids.size());
    parallelFor(used.ids.size(), threads, [&](unsigned, std::size_t begin, std::size_t end) {
        for (std::size_t rank = begin; rank < end; ++rank) {
            const std::uint32_t k = byCell[rank];
            const RefineVertex& vertex = vertices[used.ids[k]];
            rankOf[used.ids[k]] = static_cast<std::uint32_t>(rank);
            out.vertices[rank] = {vertex.position.x, vertex.position.y,
                                  static_cast<double>(vertex.z)};
            out.sourceIndex[rank] = used.cells[k];
        }
    });
}

/// The final index of each slot of `slots` (the slots in use): triangles by their lowest
/// corner's rank (counting sort: one bucket per vertex), in slot order within a bucket. Also
/// in indexOf[slot], an array over all slots (unset elsewhere).
std::vector<std::uint32_t> trianglePlaces(const RefineMesh& mesh, const std::vector<TriId>& slots,
                                          const std::uint32_t* rankOf, std::size_t vertexCount,
                                          std::int32_t* indexOf, unsigned threads) {
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
    std::vector<std::uint32_t> position(triangleCount);
    for (std::size_t k = 0; k < triangleCount; ++k) {
        position[k] = start[lowest[k]]++;
        indexOf[slots[k]] = static_cast<std::int32_t>(position[k]);
    }
    return position;
}

/// The triangles of `slots` into `out` at their places, corners as ranks, neighbours as places.
void placeTriangles(const RefineMesh& mesh, const std::vector<TriId>& slots,
                    const std::vector<std::uint32_t>& position, const std::uint32_t* rankOf,
                    const std::int32_t* indexOf, TinMesh& out, unsigned threads) {
    out.triangles.resize(3 * slots.size());
    out.neighbours.resize(3 * slots.size());
    parallelFor(slots.size(), threads, [&](unsigned, std::size_t begin, std::size_t end) {
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
}

} // namespace

TinMesh extractInCellOrder(const RefineMesh& mesh, std::span<const RefineVertex> vertices,
                           std::span<const VertexRange> ranges, std::int64_t width,
                           unsigned threads, std::vector<TriId>* slotOfTriangle,
                           std::size_t spareVertices) {
    const UsedVertices used = usedVertices(vertices, ranges, width, threads);
    // Vertices by cell. A vertex id's rank is kept in an array over all ids, unset but for
    // the ids in use: their pages only are touched.
    const std::vector<std::uint32_t> byCell = orderOfKeys(used.cells);
    VertexId idEnd = 0;
    for (const VertexRange& range : ranges)
        idEnd = std::max(idEnd, range.end);
    const std::unique_ptr<std::uint32_t[]> rankOf(new std::uint32_t[idEnd]);
    TinMesh out;
    reserveRoom(out, used.ids.size(), spareVertices);
    placeVertices(used, vertices, byCell, rankOf.get(), out, threads);

    const std::vector<TriId> slots = mesh.slotsInUse();
    // The final index of each slot in use, in an array over all slots (unset elsewhere).
    const std::unique_ptr<std::int32_t[]> indexOf(new std::int32_t[mesh.slotEnd()]);
    const std::vector<std::uint32_t> position =
        trianglePlaces(mesh, slots, rankOf.get(), used.ids.size(), indexOf.get(), threads);
    if (slotOfTriangle != nullptr) {
        slotOfTriangle->resize(slots.size());
        for (std::size_t k = 0; k < slots.size(); ++k)
            (*slotOfTriangle)[position[k]] = slots[k];
    }
    placeTriangles(mesh, slots, position, rankOf.get(), indexOf.get(), out, threads);
    return out;
}

} // namespace terratin::detail

#include "packed_rtree_order.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>
#include <tbb/parallel_sort.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace terratin::io::detail {

namespace {

/// The largest cell coordinate of GDAL's Hilbert grid (HILBERT_MAX in packedrtree.h).
constexpr double kHilbertMax = 65535.0;

/// Triangles per TBB task: enough that scheduling is noise next to the key computation.
constexpr std::size_t kGrain = 16384;

struct Extent {
    double minX = std::numeric_limits<double>::infinity();
    double minY = std::numeric_limits<double>::infinity();
    double maxX = -std::numeric_limits<double>::infinity();
    double maxY = -std::numeric_limits<double>::infinity();

    void expand(const Extent& other) {
        minX = std::min(minX, other.minX);
        minY = std::min(minY, other.minY);
        maxX = std::max(maxX, other.maxX);
        maxY = std::max(maxY, other.maxY);
    }
};

Extent triangleEnvelope(const TinMesh& mesh, std::size_t t) {
    const Point3& a = mesh.vertices[mesh.triangles[3 * t]];
    const Point3& b = mesh.vertices[mesh.triangles[3 * t + 1]];
    const Point3& c = mesh.vertices[mesh.triangles[3 * t + 2]];
    return {std::min({a.x, b.x, c.x}), std::min({a.y, b.y, c.y}), std::max({a.x, b.x, c.x}),
            std::max({a.y, b.y, c.y})};
}

/// GDAL's cell coordinate of an envelope centre: the same operations in the same order, so the
/// same rounding.
std::uint32_t cellCoordinate(double low, double high, double extentMin, double extentSize) {
    if (extentSize == 0.0)
        return 0;
    return static_cast<std::uint32_t>(
        std::floor(kHilbertMax * ((low + high) / 2 - extentMin) / extentSize));
}

} // namespace

std::uint32_t hilbertIndex16(std::uint32_t x, std::uint32_t y) {
    // From the coarsest quadrant to the finest: add the quadrant's rank times the cells of a
    // quadrant, then turn the coordinates into the frame of the sub-curve inside it (a
    // transpose, after a reflection for the lower-right quadrant). Only bits below s are read
    // afterwards, so the reflection may flip all 32 bits.
    std::uint32_t index = 0;
    for (std::uint32_t s = 1U << 15; s > 0; s /= 2) {
        const std::uint32_t rx = (x & s) != 0 ? 1 : 0;
        const std::uint32_t ry = (y & s) != 0 ? 1 : 0;
        index += s * s * ((3 * rx) ^ ry);
        if (ry == 0) {
            if (rx == 1) {
                x = ~x;
                y = ~y;
            }
            std::swap(x, y);
        }
    }
    return index;
}

std::vector<std::uint32_t> packedRtreeOrder(const TinMesh& mesh) {
    const std::size_t count = mesh.triangleCount();
    const Extent extent = tbb::parallel_reduce(
        tbb::blocked_range<std::size_t>(0, count, kGrain), Extent{},
        [&](const tbb::blocked_range<std::size_t>& range, Extent partial) {
            for (std::size_t t = range.begin(); t != range.end(); ++t)
                partial.expand(triangleEnvelope(mesh, t));
            return partial;
        },
        [](Extent a, const Extent& b) {
            a.expand(b);
            return a;
        });
    const double width = extent.maxX - extent.minX;
    const double height = extent.maxY - extent.minY;

    // Decreasing Hilbert index, then increasing triangle index: the complement of the index in
    // the high half, the triangle in the low half, sorted ascending.
    std::vector<std::uint64_t> keys(count);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, count, kGrain),
                      [&](const tbb::blocked_range<std::size_t>& range) {
                          for (std::size_t t = range.begin(); t != range.end(); ++t) {
                              const Extent box = triangleEnvelope(mesh, t);
                              const std::uint32_t hilbert = hilbertIndex16(
                                  cellCoordinate(box.minX, box.maxX, extent.minX, width),
                                  cellCoordinate(box.minY, box.maxY, extent.minY, height));
                              keys[t] = (std::uint64_t{~hilbert} << 32) | t;
                          }
                      });
    tbb::parallel_sort(keys.begin(), keys.end());

    std::vector<std::uint32_t> order(count);
    for (std::size_t i = 0; i < count; ++i)
        order[i] = static_cast<std::uint32_t>(keys[i] & 0xFFFFFFFFU);
    return order;
}

TinMesh reorderTriangles(const TinMesh& mesh, const std::vector<std::uint32_t>& order) {
    TinMesh reordered;
    reordered.vertices = mesh.vertices;
    reordered.triangles.resize(mesh.triangles.size());
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, order.size(), kGrain),
                      [&](const tbb::blocked_range<std::size_t>& range) {
                          for (std::size_t i = range.begin(); i != range.end(); ++i)
                              for (std::size_t k = 0; k < 3; ++k)
                                  reordered.triangles[3 * i + k] =
                                      mesh.triangles[3 * std::size_t{order[i]} + k];
                      });
    return reordered;
}

} // namespace terratin::io::detail

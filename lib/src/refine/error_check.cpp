#include "error_check.hpp"

#include "error_measure.hpp"

#include "../parallel/parallel_for.hpp"

#include <algorithm>
#include <cmath>

namespace terratin::detail {

namespace {

/// Triangles a thread takes at a time.
constexpr std::size_t kCheckChunk = 4096;

// Pixel corners of every vertex, computed once (a division per vertex, not per triangle).
std::vector<PixelCorner> pixelCorners(const TinMesh& mesh, std::int64_t width, unsigned threads) {
    std::vector<PixelCorner> corners(mesh.vertexCount());
    parallelFor(corners.size(), threads, [&](unsigned, std::size_t begin, std::size_t end) {
        for (std::size_t v = begin; v < end; ++v) {
            const auto cell = static_cast<std::int64_t>(mesh.sourceIndex[v]);
            corners[v] = {cell % width, cell / width, mesh.vertices[v].z,
                          static_cast<std::uint32_t>(v)};
        }
    });
    return corners;
}

[[gnu::always_inline]] inline PixelTriangle
triangleOf(const TinMesh& mesh, const std::vector<PixelCorner>& corners, std::size_t t) {
    return {corners[mesh.triangles[3 * t]], corners[mesh.triangles[3 * t + 1]],
            corners[mesh.triangles[3 * t + 2]]};
}

} // namespace

std::vector<std::uint8_t> trianglesOverOpenHoles(const TinMesh& mesh, const GridView& grid,
                                                 unsigned threads) {
    std::vector<std::uint8_t> drop(mesh.triangleCount(), 0);
    const std::vector<PixelCorner> corners = pixelCorners(mesh, grid.width, threads);
    parallelForChunks(
        drop.size(), threads, kCheckChunk, [&](unsigned, std::size_t begin, std::size_t end) {
            for (std::size_t t = begin; t < end; ++t) {
                const PixelTriangle triangle = triangleOf(mesh, corners, t);
                bool covers = false;
                if (triangle.hasArea()) {
                    triangle.forEachRow(grid.width, grid.height, nullptr,
                                        [&](std::int64_t row, std::int64_t lo, std::int64_t hi) {
                                            const std::uint8_t* flags =
                                                grid.flags + row * grid.width;
                                            for (std::int64_t col = lo; col <= hi && !covers; ++col)
                                                covers = (flags[col] & kCellOpenHole) != 0;
                                        });
                } else {
                    triangle.forEachOnSegment([&](std::int64_t col, std::int64_t row) {
                        covers |= (grid.flags[row * grid.width + col] & kCellOpenHole) != 0;
                    });
                }
                drop[t] = covers ? 1 : 0;
            }
        });
    return drop;
}

namespace {

/// Measures the valid cells of a row's interval: into the maximum, and when `count`, into
/// the sums as well.
void measureCells(const GridView& grid, const PixelTriangle& triangle, std::int64_t row,
                  std::int64_t lo, std::int64_t hi, bool count, ErrorMeasure& measure) {
    const std::uint8_t* flags = grid.flags + row * grid.width;
    const float* z = grid.z + row * grid.width;
    const double base = triangle.rowBase(row);
    const double gradCol = triangle.gradCol();
    // Sums in locals: `measure` might alias the flags (bytes alias anything), which would
    // keep it in memory, a store and a reload per cell.
    double maxError = measure.maxError;
    double sumSquares = 0.0;
    std::size_t cells = 0;
    for (std::int64_t col = lo; col <= hi; ++col) {
        if (flags[col] != 0)
            continue;
        const double error = cellError(z[col], base + gradCol * static_cast<double>(col));
        maxError = std::max(maxError, error);
        sumSquares += error * error;
        ++cells;
    }
    measure.maxError = maxError;
    if (count) {
        measure.sumSquares += sumSquares;
        measure.coveredCells += cells;
    }
}

/// 1 for each triangle without pixel area (pixel-collinear corners), which the check skips:
/// its cells lie on its neighbours' edges.
std::vector<std::uint8_t> flatInPixels(const TinMesh& mesh, const std::vector<PixelCorner>& corners,
                                       unsigned threads) {
    const std::size_t triangles = mesh.triangleCount();
    std::vector<std::uint8_t> flat(triangles);
    parallelFor(triangles, threads, [&](unsigned, std::size_t begin, std::size_t end) {
        for (std::size_t t = begin; t < end; ++t) {
            const PixelCorner& a = corners[mesh.triangles[3 * t]];
            const PixelCorner& b = corners[mesh.triangles[3 * t + 1]];
            const PixelCorner& c = corners[mesh.triangles[3 * t + 2]];
            flat[t] =
                (b.col - a.col) * (c.row - a.row) == (c.col - a.col) * (b.row - a.row) ? 1 : 0;
        }
    });
    return flat;
}

/// Measures the cells of triangle t (with pixel area) into `measure`: each covered cell
/// counted in the one triangle that owns it, which sees the largest error as well.
void measureTriangle(const TinMesh& mesh, const std::vector<PixelCorner>& corners,
                     const std::vector<std::uint8_t>& flat, std::size_t t, const GridView& grid,
                     ErrorMeasure& measure) {
    const PixelTriangle triangle = triangleOf(mesh, corners, t);
    if (triangle.coversOnlyCorners())
        return; // vertices, counted by the caller
    // Edge i of `triangle` runs corner(i) -> corner(i+1); the mesh's neighbour across it is
    // the one across the mesh edge opposite corner(i+2), mesh corner k, which is the mesh edge
    // k + 1 (TinMesh: neighbours[3t+j] across corner j to j+1).
    bool strict[3] = {false, false, false};
    bool besideFlat = false;
    for (int i = 0; i < 3; ++i) {
        const std::uint32_t opposite = triangle.corner((i + 2) % 3).id;
        const std::size_t k = opposite == mesh.triangles[3 * t]       ? 0
                              : opposite == mesh.triangles[3 * t + 1] ? 1
                                                                      : 2;
        const std::int32_t neighbour = mesh.neighbours[3 * t + (k + 1) % 3];
        strict[i] = neighbour != kNoNeighbour && !triangle.ownsSharedEdge(i);
        besideFlat |= neighbour != kNoNeighbour && flat[static_cast<std::size_t>(neighbour)];
    }
    // No triangle owns the cells a flat neighbour skips, so beside one the maximum takes every
    // cell of the closed triangle.
    triangle.forEachRow(grid.width, grid.height, strict,
                        [&](std::int64_t row, std::int64_t lo, std::int64_t hi) {
                            measureCells(grid, triangle, row, lo, hi, true, measure);
                        });
    if (besideFlat)
        triangle.forEachRow(grid.width, grid.height, nullptr,
                            [&](std::int64_t row, std::int64_t lo, std::int64_t hi) {
                                measureCells(grid, triangle, row, lo, hi, false, measure);
                            });
}

} // namespace

ErrorMeasure measureErrors(const TinMesh& mesh, const GridView& grid, unsigned threads) {
    const std::size_t triangles = mesh.triangleCount();
    std::vector<ErrorMeasure> blocks(parallelForThreads(triangles, threads));
    const std::vector<PixelCorner> corners = pixelCorners(mesh, grid.width, threads);
    const std::vector<std::uint8_t> flat = flatInPixels(mesh, corners, threads);
    // Chunks, not halves: triangles differ in size by orders of magnitude (flat ground).
    parallelForChunks(
        triangles, threads, kCheckChunk, [&](unsigned block, std::size_t begin, std::size_t end) {
            for (std::size_t t = begin; t < end; ++t) {
                // Corners are looked up by vertex number, at random: ask for them ahead.
                constexpr std::size_t kAhead = 8;
                if (t + kAhead < end)
                    for (std::size_t k = 0; k < 3; ++k)
                        __builtin_prefetch(&corners[mesh.triangles[3 * (t + kAhead) + k]]);
                if (flat[t] == 0)
                    measureTriangle(mesh, corners, flat, t, grid, blocks[block]);
            }
        });
    ErrorMeasure total;
    for (const ErrorMeasure& block : blocks) {
        total.maxError = std::max(total.maxError, block.maxError);
        total.sumSquares += block.sumSquares;
        total.coveredCells += block.coveredCells;
    }
    total.coveredCells += mesh.vertexCount();
    return total;
}

} // namespace terratin::detail

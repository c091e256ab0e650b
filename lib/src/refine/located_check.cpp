#include "located_check.hpp"

#include "error_measure.hpp"

#include "../parallel/parallel_for.hpp"

#include "terratin/geometry/predicates.hpp"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace terratin::detail {

namespace {

Point2 planar(const Point3& p) {
    return {p.x, p.y};
}

/// Locates cells in a TinMesh by a visibility walk from the last triangle found, and gives
/// the TIN's elevation there. Consecutive cells mostly lie in the same triangle, whose
/// corners, links and plane are kept from one cell to the next.
class CellWalker {
public:
    CellWalker(const TinMesh& mesh, const GridView& grid, std::span<const Point2> positions)
        : m_mesh(&mesh), m_width(grid.width), m_positions(positions) {
        m_current = load(0);
    }

    /// The triangle whose closed triangle holds q, or -1 when q is outside the hull (the
    /// walk then stays at the hull, where the next cell most likely is).
    std::int64_t locate(const Point2& q) {
        const std::size_t triangles = m_mesh->triangleCount();
        // A visibility walk on a Delaunay triangulation visits no triangle twice; more steps
        // than triangles means the mesh broke its precondition.
        for (std::size_t steps = 0; steps <= triangles; ++steps) {
            const std::array<Point2, 3>& p = m_current.corners;
            int exit = -1;
            m_onEdge = 0;
            for (int i = 0; i < 3 && exit < 0; ++i) {
                const double side = predicates::orient2d(
                    p[static_cast<std::size_t>(i)], p[static_cast<std::size_t>((i + 1) % 3)], q);
                if (side < 0.0)
                    exit = i;
                else if (side == 0.0)
                    m_onEdge |= 1U << static_cast<unsigned>(i);
            }
            if (exit < 0)
                return static_cast<std::int64_t>(m_current.id);
            const std::int32_t across = m_current.neighbours[static_cast<std::size_t>(exit)];
            if (across == kNoNeighbour)
                return -1; // beyond a hull edge: outside the convex hull
            m_current = load(static_cast<std::size_t>(across));
        }
        throw std::logic_error("Refiner: the point walk does not end; the TIN is not Delaunay");
    }

    /// Whether the last located point lies on an edge of its triangle.
    [[nodiscard]] bool onEdge() const { return m_onEdge != 0; }

    /// Continues the next walk from triangle t.
    void restartAt(std::size_t t) {
        if (t != m_current.id)
            m_current = load(t);
    }

    /// Calls visit(s) for the triangle t that the last locate() found and, when the point lies
    /// on one of its edges, for the neighbour across it (closed triangles).
    template <class Visit> void forEachHolding(std::size_t t, Visit&& visit) const {
        visit(t);
        for (std::size_t i = 0; i < 3; ++i) {
            const std::int32_t across = m_current.neighbours[i];
            if ((m_onEdge & (1U << i)) != 0 && across != kNoNeighbour)
                visit(static_cast<std::size_t>(across));
        }
    }

    /// The TIN's elevation at the position of `cell`, which triangle t holds: its plane's, or
    /// for a triangle whose corners are collinear in the grid, the linear interpolation along
    /// that grid line between the two corners around the cell. Such a triangle is the
    /// projection's bending of a straight row, column or diagonal (rounding can make it a
    /// sliver of 1e-13 m^2 along a straight one, on the hull); its plane means nothing, and a
    /// cell it holds lies on its grid line (any other cell is a whole cell away from it).
    [[nodiscard]] double elevation(std::size_t t, std::size_t cell) const {
        if (t == m_current.id)
            return elevation(m_current, cell);
        return elevation(load(t), cell);
    }

private:
    struct Pixel {
        std::int64_t col;
        std::int64_t row;
        double z;
    };
    /// What the walk and the interpolation need of a triangle.
    struct Triangle {
        std::size_t id = 0;
        std::array<Point2, 3> corners;
        std::array<std::int32_t, 3> neighbours;
        std::array<Pixel, 3> pixels;
        bool collinearInGrid = false;
        /// The plane: z = z0 + gradX (x - corners[0].x) + gradY (y - corners[0].y).
        double z0 = 0.0;
        double gradX = 0.0;
        double gradY = 0.0;
    };

    [[nodiscard]] Triangle load(std::size_t t) const {
        Triangle triangle;
        triangle.id = t;
        std::array<Point3, 3> v;
        for (std::size_t i = 0; i < 3; ++i) {
            const std::uint32_t vertex = m_mesh->triangles[3 * t + i];
            v[i] = m_mesh->vertices[vertex];
            triangle.corners[i] = planar(v[i]);
            triangle.neighbours[i] = m_mesh->neighbours[3 * t + i];
            const auto cell = static_cast<std::int64_t>(m_mesh->sourceIndex[vertex]);
            triangle.pixels[i] = {cell % m_width, cell / m_width, v[i].z};
        }
        const std::array<Pixel, 3>& px = triangle.pixels;
        triangle.collinearInGrid = (px[1].col - px[0].col) * (px[2].row - px[0].row) ==
                                   (px[2].col - px[0].col) * (px[1].row - px[0].row);
        const double bx = v[1].x - v[0].x;
        const double by = v[1].y - v[0].y;
        const double bz = v[1].z - v[0].z;
        const double cx = v[2].x - v[0].x;
        const double cy = v[2].y - v[0].y;
        const double cz = v[2].z - v[0].z;
        const double twiceArea = bx * cy - by * cx;
        triangle.z0 = v[0].z;
        if (!triangle.collinearInGrid) {
            triangle.gradX = (bz * cy - cz * by) / twiceArea;
            triangle.gradY = (cz * bx - bz * cx) / twiceArea;
        }
        return triangle;
    }

    [[nodiscard]] double elevation(const Triangle& triangle, std::size_t cell) const {
        if (!triangle.collinearInGrid) {
            const Point2& q = m_positions[cell];
            return triangle.z0 + triangle.gradX * (q.x - triangle.corners[0].x) +
                   triangle.gradY * (q.y - triangle.corners[0].y);
        }
        return alongGridLine(triangle.pixels, {static_cast<std::int64_t>(cell) % m_width,
                                               static_cast<std::int64_t>(cell) / m_width, 0.0});
    }

    /// Linear interpolation at q between the corners just before and after it along their
    /// common grid line, parametrised by the line's longer pixel axis (exact integers).
    static double alongGridLine(const std::array<Pixel, 3>& corners, const Pixel& q) {
        std::int64_t spanCol = 0;
        std::int64_t spanRow = 0;
        for (const Pixel& p : corners) {
            spanCol = std::max(spanCol, std::abs(p.col - corners[0].col));
            spanRow = std::max(spanRow, std::abs(p.row - corners[0].row));
        }
        const auto along = [byCol = spanCol >= spanRow](const Pixel& p) {
            return byCol ? p.col : p.row;
        };
        const Pixel* before = nullptr;
        const Pixel* after = nullptr;
        for (const Pixel& p : corners) {
            if (along(p) <= along(q) && (before == nullptr || along(p) > along(*before)))
                before = &p;
            if (along(p) >= along(q) && (after == nullptr || along(p) < along(*after)))
                after = &p;
        }
        if (before == nullptr)
            return after->z;
        if (after == nullptr || along(*after) == along(*before))
            return before->z;
        const double fraction = static_cast<double>(along(q) - along(*before)) /
                                static_cast<double>(along(*after) - along(*before));
        return before->z + fraction * (after->z - before->z);
    }

    /// The caller's, outliving the walker (never null).
    const TinMesh* m_mesh;
    std::int64_t m_width;
    std::span<const Point2> m_positions;
    Triangle m_current;
    /// Bit i: the last located point lies on edge i of m_current.
    unsigned m_onEdge = 0;
};

/// Calls visit(block, walker, cell, t) for every cell c with `wanted(flags[c])` that lies in
/// the mesh (t: the triangle the walk found), the cells split into contiguous blocks, one
/// walker each. With a memo, the cells it marks unchanged are skipped, and the walk after a
/// skip starts at the cell's `near` triangle.
template <class Wanted, class Visit>
void forEachCellLocated(const TinMesh& mesh, const GridView& grid,
                        std::span<const Point2> positions, unsigned threads, Wanted&& wanted,
                        Visit&& visit, const CheckMemo* memo = nullptr) {
    const auto cells = static_cast<std::size_t>(grid.width * grid.height);
    if (positions.size() != cells)
        throw std::invalid_argument("Refiner: one position per cell is needed");
    const bool skipping = memo != nullptr && !memo->unchanged.empty();
    const auto width = static_cast<std::size_t>(grid.width);
    parallelFor(cells, threads, [&](unsigned block, std::size_t begin, std::size_t end) {
        CellWalker walker(mesh, grid, positions);
        // Each row starts its walk where the previous one started, a row away, rather than
        // at the previous row's far end.
        std::int64_t rowStart = -1;
        bool rowStartPending = true;
        bool skipped = false;
        for (std::size_t cell = begin; cell < end; ++cell) {
            if (cell % width == 0) {
                if (rowStart >= 0)
                    walker.restartAt(static_cast<std::size_t>(rowStart));
                rowStartPending = true;
            }
            if (!wanted(grid.flags[cell]))
                continue;
            if (skipping) {
                if (memo->unchanged[cell] != 0) {
                    skipped = true;
                    continue;
                }
                if (skipped && memo->near[cell] >= 0)
                    walker.restartAt(static_cast<std::size_t>(memo->near[cell]));
                skipped = false;
            }
            const std::int64_t t = walker.locate(positions[cell]);
            if (rowStartPending && t >= 0) {
                rowStart = t;
                rowStartPending = false;
            }
            if (t >= 0)
                visit(block, walker, cell, static_cast<std::size_t>(t));
        }
    });
}

bool isMeasured(std::uint8_t flags) {
    return (flags & (kCellNoData | kCellVertex)) == 0;
}

} // namespace

std::vector<std::uint8_t> trianglesOverOpenHolesAt(const TinMesh& mesh, const GridView& grid,
                                                   std::span<const Point2> positions,
                                                   unsigned threads) {
    std::vector<std::uint8_t> drop(mesh.triangleCount(), 0);
    // Different blocks may mark the same triangle: the flags are written through atomic_ref.
    forEachCellLocated(
        mesh, grid, positions, threads,
        [](std::uint8_t flags) { return (flags & kCellOpenHole) != 0; },
        [&](unsigned, const CellWalker& walker, std::size_t, std::size_t t) {
            walker.forEachHolding(t, [&](std::size_t s) {
                std::atomic_ref<std::uint8_t>(drop[s]).store(1, std::memory_order_relaxed);
            });
        });
    return drop;
}

ErrorMeasure measureErrorsAt(const TinMesh& mesh, std::span<const std::uint8_t> drop,
                             const GridView& grid, std::span<const Point2> positions,
                             unsigned threads) {
    const auto cells = static_cast<std::size_t>(grid.width * grid.height);
    std::vector<ErrorMeasure> blocks(parallelForThreads(cells, threads));
    forEachCellLocated(
        mesh, grid, positions, threads, isMeasured,
        [&](unsigned block, const CellWalker& walker, std::size_t cell, std::size_t t) {
            ErrorMeasure& measure = blocks[block];
            bool counted = false;
            walker.forEachHolding(t, [&](std::size_t s) {
                if (drop[s] != 0)
                    return;
                const double error = cellError(grid.z[cell], walker.elevation(s, cell));
                measure.maxError = std::max(measure.maxError, error);
                if (!counted) {
                    measure.sumSquares += error * error;
                    ++measure.coveredCells;
                    counted = true;
                }
            });
        });
    ErrorMeasure total;
    for (const ErrorMeasure& block : blocks) {
        total.maxError = std::max(total.maxError, block.maxError);
        total.sumSquares += block.sumSquares;
        total.coveredCells += block.coveredCells;
    }
    // The vertices of kept triangles: exact, each once.
    std::vector<std::uint8_t> kept(mesh.vertexCount(), 0);
    for (std::size_t t = 0; t < mesh.triangleCount(); ++t)
        if (drop[t] == 0)
            for (std::size_t i = 0; i < 3; ++i)
                kept[mesh.triangles[3 * t + i]] = 1;
    total.coveredCells += static_cast<std::size_t>(std::count(kept.begin(), kept.end(), 1));
    return total;
}

std::vector<CellToInsert> cellsToInsertAt(const TinMesh& mesh, const GridView& grid,
                                          std::span<const Point2> positions, double threshold,
                                          unsigned threads, const CheckMemo* memo) {
    const std::vector<std::uint8_t> overHole =
        trianglesOverOpenHolesAt(mesh, grid, positions, threads);
    struct Found {
        std::uint32_t triangle;
        std::uint32_t cell;
        double error;
    };
    const auto cells = static_cast<std::size_t>(grid.width * grid.height);
    std::vector<std::vector<Found>> blocks(parallelForThreads(cells, threads));
    forEachCellLocated(
        mesh, grid, positions, threads, isMeasured,
        [&](unsigned block, const CellWalker& walker, std::size_t cell, std::size_t t) {
            if (memo != nullptr)
                memo->located[cell] = walker.onEdge() ? -1 : static_cast<std::int32_t>(t);
            walker.forEachHolding(t, [&](std::size_t s) {
                const double error = cellError(grid.z[cell], walker.elevation(s, cell));
                if (overHole[s] != 0 || error > threshold)
                    blocks[block].push_back(
                        {static_cast<std::uint32_t>(s), static_cast<std::uint32_t>(cell), error});
            });
        },
        memo);
    std::vector<Found> found;
    for (const std::vector<Found>& block : blocks)
        found.insert(found.end(), block.begin(), block.end());
    // Per triangle the farthest cell, ties to the lowest index: the result does not depend
    // on how the cells were split between threads.
    std::sort(found.begin(), found.end(), [](const Found& a, const Found& b) {
        if (a.triangle != b.triangle)
            return a.triangle < b.triangle;
        return a.error != b.error ? a.error > b.error : a.cell < b.cell;
    });
    std::vector<CellToInsert> result;
    for (std::size_t i = 0; i < found.size(); ++i)
        if (i == 0 || found[i].triangle != found[i - 1].triangle)
            result.push_back({found[i].cell, found[i].triangle,
                              overHole[found[i].triangle] != 0
                                  ? std::numeric_limits<double>::infinity()
                                  : found[i].error});
    std::sort(result.begin(), result.end(), [](const CellToInsert& a, const CellToInsert& b) {
        return a.cell != b.cell ? a.cell < b.cell : a.triangle < b.triangle;
    });
    result.erase(
        std::unique(result.begin(), result.end(),
                    [](const CellToInsert& a, const CellToInsert& b) { return a.cell == b.cell; }),
        result.end());
    return result;
}

} // namespace terratin::detail

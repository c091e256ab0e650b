#include "stranded_cells.hpp"

#include "level_schedule.hpp"

#include "terratin/error.hpp"
#include "terratin/geometry/predicates.hpp"

#include <algorithm>
#include <array>

namespace terratin::detail {

namespace {

/// A cell's pixel coordinates (column, row): integers, exact in a double.
Point2 pixelOf(std::uint32_t cell, std::int64_t width) {
    return {static_cast<double>(static_cast<std::int64_t>(cell) % width),
            static_cast<double>(static_cast<std::int64_t>(cell) / width)};
}

/// Sign of the turn a -> b -> p (exact): > 0 left, 0 on the line.
int turn(Point2 a, Point2 b, Point2 p) {
    const double cross = predicates::orient2d(a, b, p);
    return cross > 0.0 ? 1 : (cross < 0.0 ? -1 : 0);
}

/// The triangle of `mesh` holding `target` (closed), by a visibility walk from `start`: it
/// ends in a Delaunay triangulation of a convex region holding the point.
std::uint32_t walkTo(const TinMesh& mesh, std::uint32_t start, Point2 target, std::int64_t width) {
    std::uint32_t t = start;
    for (std::size_t steps = 0; steps <= mesh.triangleCount(); ++steps) {
        std::array<Point2, 3> corner;
        for (std::size_t k = 0; k < 3; ++k)
            corner[k] = pixelOf(mesh.sourceIndex[mesh.triangles[3 * t + k]], width);
        // Counter-clockwise in the TIN's coordinates; the grid's rows may run the other way.
        const int inside = turn(corner[0], corner[1], corner[2]);
        std::size_t across = 3;
        for (std::size_t e = 0; e < 3 && across == 3; ++e)
            if (turn(corner[e], corner[(e + 1) % 3], target) * inside < 0)
                across = e;
        if (across == 3)
            return t;
        const std::int32_t next = mesh.neighbours[3 * t + across];
        if (next == kNoNeighbour)
            break;
        t = static_cast<std::uint32_t>(next);
    }
    throw Error("Refiner: a cell beside a vertex stranded by a hole lies in no triangle");
}

} // namespace

std::vector<CellToInsert> cellsBesideStrandedVertices(const TinMesh& mesh,
                                                      std::span<const std::uint8_t> drop,
                                                      const GridView& grid) {
    std::vector<std::uint8_t> kept(mesh.vertexCount(), 0);
    for (std::size_t t = 0; t < mesh.triangleCount(); ++t)
        if (drop[t] == 0)
            for (std::size_t k = 0; k < 3; ++k)
                kept[mesh.triangles[3 * t + k]] = 1;
    std::vector<CellToInsert> cells;
    if (std::all_of(kept.begin(), kept.end(), [](std::uint8_t k) { return k != 0; }))
        return cells;
    std::vector<std::uint32_t> triangleOf(mesh.vertexCount(), 0); // a triangle of each vertex
    for (std::size_t t = 0; t < mesh.triangleCount(); ++t)
        for (std::size_t k = 0; k < 3; ++k)
            triangleOf[mesh.triangles[3 * t + k]] = static_cast<std::uint32_t>(t);
    constexpr std::uint8_t kNotInsertable = kCellNoData | kCellVertex | kCellFrozen;
    for (std::size_t v = 0; v < mesh.vertexCount(); ++v) {
        if (kept[v] != 0)
            continue;
        forEachCellAround(
            mesh.sourceIndex[v], grid.width, grid.height,
            [&](std::uint32_t cell, std::int64_t row, std::int64_t col) {
                if ((grid.flags[cell] & kNotInsertable) != 0)
                    return;
                const Point2 target{static_cast<double>(col), static_cast<double>(row)};
                cells.push_back(
                    {cell, walkTo(mesh, triangleOf[v], target, grid.width), kHolePriority});
            });
    }
    std::sort(cells.begin(), cells.end(),
              [](const CellToInsert& a, const CellToInsert& b) { return a.cell < b.cell; });
    cells.erase(
        std::unique(cells.begin(), cells.end(),
                    [](const CellToInsert& a, const CellToInsert& b) { return a.cell == b.cell; }),
        cells.end());
    return cells;
}

std::vector<CellToInsert>
cellsBesideStrandedVertices(const HeightGrid& grid, const TinMesh& mesh,
                            std::span<const std::uint8_t> drop,
                            std::span<const std::uint8_t> overHoleOnly,
                            const std::function<bool(std::size_t cell)>& insertable) {
    constexpr std::uint8_t kKept = 1;
    constexpr std::uint8_t kOverHole = 2;
    constexpr std::uint32_t kNoTriangleYet = 0xffffffffU;
    std::vector<std::uint8_t> uses(mesh.vertexCount(), 0);
    std::vector<std::uint32_t> triangleOf(mesh.vertexCount(), kNoTriangleYet);
    for (std::size_t t = 0; t < mesh.triangleCount(); ++t)
        for (std::size_t i = 0; i < 3; ++i) {
            const std::uint32_t v = mesh.triangles[3 * t + i];
            if (drop[t] == 0)
                uses[v] |= kKept;
            else if (overHoleOnly[t] != 0)
                uses[v] |= kOverHole;
            triangleOf[v] = static_cast<std::uint32_t>(t);
        }
    std::vector<std::uint8_t> isVertex(grid.cellCount(), 0);
    for (const std::uint32_t cell : mesh.sourceIndex)
        if (cell < grid.cellCount())
            isVertex[cell] = 1;
    std::vector<CellToInsert> cells;
    for (std::size_t v = 0; v < mesh.vertexCount(); ++v) {
        if (uses[v] != kOverHole || mesh.sourceIndex[v] >= grid.cellCount())
            continue;
        forEachCellAround(mesh.sourceIndex[v], grid.width, grid.height,
                          [&](std::uint32_t cell, std::int64_t, std::int64_t) {
                              if (!grid.isValid(cell) || isVertex[cell] != 0 ||
                                  (insertable && !insertable(cell)))
                                  return;
                              isVertex[cell] = 1; // once
                              cells.push_back({cell, triangleOf[v], kHolePriority});
                          });
    }
    std::sort(cells.begin(), cells.end(),
              [](const CellToInsert& a, const CellToInsert& b) { return a.cell < b.cell; });
    return cells;
}

} // namespace terratin::detail

// CompletionCheck: locating the measured cells and the open holes' cells in the constrained
// TIN (completion_check.hpp), once and then after each round of insertions.

#include "completion_check.hpp"

#include "cell_in_triangle.hpp"
#include "error_measure.hpp"

#include <cmath>

namespace terratin::detail {

void CompletionCheck::relocate(const std::vector<std::uint8_t>& changed) {
    // The locator is built once and only copied, so that every walk starts from the same
    // state: which triangle a cell on an edge gets does not depend on the threads. Later
    // the cells of changed triangles walk from their old triangle, whose slot now holds a
    // triangle near it.
    if (!m_locator)
        m_locator.emplace(m_tin->mesh, m_threads);
    const bool first = changed.empty();
    if (first)
        placeVertexCells();
    relocateHoleCells(changed);
    if (first)
        locateEveryCell();
    else
        relocateCellsOf(changed);
}

void CompletionCheck::locateEveryCell() {
    forEachBlock(m_rules->measuredCells.size(),
                 [&](std::size_t, std::size_t begin, std::size_t end) {
                     std::optional<TinLocator> blockLocator;
                     std::uint32_t previous = kOutsideHull;
                     for (std::size_t i = begin; i < end; ++i) {
                         if (m_cellTriangle[i] == kOutsideHull) {
                             if (!blockLocator)
                                 blockLocator.emplace(*m_locator);
                             measureAt(i, *blockLocator, previous);
                         }
                         if (m_cellTriangle[i] != kOutsideHull)
                             previous = m_cellTriangle[i];
                     }
                 });
    m_relocated.clear();
    m_relocatedAll = true;
}

void CompletionCheck::relocateCellsOf(const std::vector<std::uint8_t>& changed) {
    const std::size_t count = m_rules->measuredCells.size();
    std::vector<std::vector<std::size_t>> relocated((count + kCellBlock - 1) / kCellBlock);
    forEachBlock(count, [&](std::size_t block, std::size_t begin, std::size_t end) {
        std::optional<TinLocator> blockLocator;
        for (std::size_t i = begin; i < end; ++i) {
            if (!stale(m_cellTriangle[i], changed))
                continue;
            if (!blockLocator)
                blockLocator.emplace(*m_locator);
            measureAt(i, *blockLocator, m_cellTriangle[i]);
            relocated[block].push_back(i);
        }
    });
    m_relocated.clear();
    m_relocatedAll = false;
    for (const std::vector<std::size_t>& cells : relocated)
        m_relocated.insert(m_relocated.end(), cells.begin(), cells.end());
}

void CompletionCheck::relocateHoleCells(const std::vector<std::uint8_t>& changed) {
    const std::vector<std::size_t>& cells = m_rules->openHoleCells;
    forEachBlock(cells.size(), [&](std::size_t, std::size_t begin, std::size_t end) {
        std::optional<TinLocator> blockLocator;
        for (std::size_t i = begin; i < end; ++i) {
            if (!stale(m_holeTriangle[i], changed))
                continue;
            if (!blockLocator)
                blockLocator.emplace(*m_locator);
            m_holeTriangle[i] = blockLocator->locateNearFrom(position(cells[i]), m_holeTriangle[i])
                                    .value_or(kOutsideHull);
        }
    });
}

void CompletionCheck::placeVertexCells() {
    constexpr std::uint32_t kNotMeasured = 0xffffffffU;
    const std::vector<std::size_t>& cells = m_rules->measuredCells;
    std::vector<std::uint32_t> measuredIndex(m_grid->cellCount(), kNotMeasured);
    parallelFor(cells.size(), m_threads, [&](unsigned, std::size_t begin, std::size_t end) {
        for (std::size_t i = begin; i < end; ++i) // distinct cells
            measuredIndex[cells[i]] = static_cast<std::uint32_t>(i);
    });
    const TinMesh& mesh = m_tin->mesh;
    std::vector<std::uint32_t> vertexTriangle(mesh.vertexCount(), kOutsideHull);
    // Downwards, so that the lowest triangle writes last: on one thread, where an atomic
    // minimum per corner on the threads is slower (docs/benchmarks.md).
    for (std::size_t t = mesh.triangleCount(); t-- > 0;)
        for (std::size_t k = 0; k < 3; ++k)
            vertexTriangle[mesh.triangles[3 * t + k]] = static_cast<std::uint32_t>(t);
    parallelFor(mesh.vertexCount(), m_threads, [&](unsigned, std::size_t begin, std::size_t end) {
        for (std::size_t v = begin; v < end; ++v) {
            const std::uint32_t cell = mesh.sourceIndex[v];
            if (cell >= measuredIndex.size() || measuredIndex[cell] == kNotMeasured)
                continue;
            const Point3& at = mesh.vertices[v];
            const Point2 p = position(cell);
            if (at.x != p.x || at.y != p.y)
                continue;
            // Only this vertex lies at the cell's position: no other thread writes cell i.
            const std::uint32_t i = measuredIndex[cell];
            m_cellTriangle[i] = vertexTriangle[v];
            m_cellError[i] = cellError(m_grid->z[cell], at.z);
            m_cellAtCorner[i] = 1;
        }
    });
}

void CompletionCheck::measureAt(std::size_t i, TinLocator& locator, std::uint32_t start) {
    const std::size_t cell = m_rules->measuredCells[i];
    const Point2 p = position(cell);
    const std::uint32_t t = locator.locateNearFrom(p, start).value_or(kOutsideHull);
    m_cellTriangle[i] = t;
    if (t == kOutsideHull)
        return;
    // Measured while the walk has the triangle's corners in cache: the tally, a pass
    // over every cell later, then reads no corner.
    m_cellError[i] = cellError(m_grid->z[cell], planeAt(m_tin->mesh, t, p));
    m_cellAtCorner[i] = isCorner(m_tin->mesh, t, p) ? 1 : 0;
}

} // namespace terratin::detail

#include "completion_check.hpp"

#include "cell_in_triangle.hpp"
#include "level_schedule.hpp"

#include <algorithm>
#include <limits>

namespace terratin::detail {

CompletionCheck::CompletionCheck(const HeightGrid& grid, std::span<const Point2> positions,
                                 const ConstrainedTin& tin, const CompletionRules& rules,
                                 std::optional<double> maxError, unsigned threads)
    : m_grid(&grid), m_positions(positions), m_tin(&tin), m_rules(&rules), m_maxError(maxError),
      m_threads(std::max(threads, 1U)) {
    m_cellTriangle.assign(rules.measuredCells.size(), kOutsideHull);
    m_cellError.assign(rules.measuredCells.size(), 0.0);
    m_cellAtCorner.assign(rules.measuredCells.size(), 0);
    m_holeTriangle.assign(rules.openHoleCells.size(), kOutsideHull);
}

CompletionMeasure CompletionCheck::measure(const std::vector<std::uint8_t>& changed, bool everyCell,
                                           std::vector<double>* squaredErrors) {
    relocate(changed);
    const std::size_t triangles = m_tin->mesh.triangleCount();
    CompletionMeasure measure;
    measure.holeTriangles = markTrianglesLeftOut();
    m_candidateOf.resize(triangles, kNoCandidate);
    // The first check locates every cell: they are all measured, as with everyCell.
    const bool allCells = everyCell || m_relocatedAll;
    const std::size_t count = allCells ? m_rules->measuredCells.size() : m_relocated.size();
    if (squaredErrors != nullptr)
        squaredErrors->assign(count, std::numeric_limits<double>::quiet_NaN());
    std::vector<BlockTally> blocks((count + kCellBlock - 1) / kCellBlock);
    forEachBlock(count, [&](std::size_t block, std::size_t begin, std::size_t end) {
        for (std::size_t k = begin; k < end; ++k) {
            const std::size_t i = allCells ? k : m_relocated[k];
            tally(i, blocks[block], squaredErrors != nullptr ? &(*squaredErrors)[i] : nullptr);
        }
    });
    for (const BlockTally& block : blocks) {
        measure.maxError = std::max(measure.maxError, block.maxError);
        measure.sumSquares += block.sumSquares;
        measure.covered += block.covered;
        measure.uncovered += block.uncovered;
        for (const CellToInsert& candidate : block.proposals)
            propose(candidate, measure);
    }
    for (const CellToInsert& candidate : measure.candidates)
        m_candidateOf[candidate.triangle] = kNoCandidate;
    if (everyCell)
        dropTriangles(measure);
    return measure;
}

std::size_t CompletionCheck::markTrianglesLeftOut() {
    for (const std::uint32_t t : m_overHoleMarked)
        if (t < m_left.size())
            m_left[t] &= static_cast<std::uint8_t>(~kOverHole);
    m_overHoleMarked.clear();
    m_left.resize(m_tin->mesh.triangleCount(), 0);
    if (m_rules->outsideArea || m_rules->unmeasured)
        markRulesLeftOut();
    return markTrianglesOverHoles();
}

void CompletionCheck::markRulesLeftOut() {
    const std::vector<std::uint8_t> outside =
        m_rules->outsideArea ? m_rules->outsideArea(*m_tin) : std::vector<std::uint8_t>{};
    const std::vector<std::uint8_t> flat =
        m_rules->unmeasured ? m_rules->unmeasured(*m_tin) : std::vector<std::uint8_t>{};
    parallelFor(m_left.size(), m_threads, [&](unsigned, std::size_t begin, std::size_t end) {
        for (std::size_t t = begin; t < end; ++t) {
            const bool dropped = !outside.empty() && outside[t] != 0;
            const bool isFlat = !flat.empty() && flat[t] != 0;
            m_left[t] = static_cast<std::uint8_t>((dropped ? kDropped : 0) | (isFlat ? kFlat : 0));
        }
    });
}

void CompletionCheck::dropTriangles(CompletionMeasure& measure) const {
    measure.drop.resize(m_left.size());
    measure.overHoleOnly.resize(m_left.size());
    parallelFor(m_left.size(), m_threads, [&](unsigned, std::size_t begin, std::size_t end) {
        for (std::size_t t = begin; t < end; ++t) {
            const std::uint8_t left = m_left[t];
            measure.drop[t] = (left & (kDropped | kOverHole)) != 0 ? 1 : 0;
            measure.overHoleOnly[t] = (left & (kOverHole | kDropped)) == kOverHole ? 1 : 0;
        }
    });
}

std::size_t CompletionCheck::markTrianglesOverHoles() {
    const TinMesh& mesh = m_tin->mesh;
    std::size_t keptByTheArea = 0;
    const auto mark = [&](std::size_t t) {
        if ((m_left[t] & kOverHole) != 0)
            return;
        m_left[t] |= kOverHole;
        m_overHoleMarked.push_back(static_cast<std::uint32_t>(t));
        keptByTheArea += (m_left[t] & kDropped) == 0 ? 1 : 0;
    };
    for (std::size_t i = 0; i < m_holeTriangle.size(); ++i) {
        const std::uint32_t t = m_holeTriangle[i];
        if (t == kOutsideHull)
            continue;
        mark(t);
        const std::int32_t other = neighbourSharing(mesh, t, position(m_rules->openHoleCells[i]));
        if (other != kNoNeighbour)
            mark(static_cast<std::size_t>(other));
    }
    return keptByTheArea;
}

void CompletionCheck::tally(std::size_t i, BlockTally& block, double* squaredError) const {
    std::uint32_t t = m_cellTriangle[i];
    if (t == kOutsideHull) {
        ++block.uncovered;
        return;
    }
    const std::size_t cell = m_rules->measuredCells[i];
    bool corner = m_cellAtCorner[i] != 0;
    if (m_left[t] != 0) {
        // A cell on an edge or at a vertex belongs to a kept triangle beside, if there is
        // one (its error there is the same: the planes meet along the edge).
        const std::int32_t other = keptTriangleAt(m_tin->mesh, t, position(cell), m_left);
        if (other != kNoNeighbour) {
            t = static_cast<std::uint32_t>(other);
            corner = isCorner(m_tin->mesh, t, position(cell));
        }
    }
    if ((m_left[t] & (kDropped | kFlat)) != 0)
        return; // outside the output's area, or in a replace area
    // Asked only of a cell about to be proposed: the rule may be a call per cell.
    const auto insertable = [&] {
        return !corner && (!m_rules->insertable || m_rules->insertable(cell));
    };
    const auto asCandidate = [&](double priority) {
        return CellToInsert{static_cast<std::uint32_t>(cell), t, priority};
    };
    if ((m_left[t] & kOverHole) != 0 && !corner) {
        // As the refiner does: a hole's triangle is split until it covers no valid cell.
        ++block.uncovered;
        if (insertable())
            block.proposals.push_back(asCandidate(kHolePriority));
        return;
    }
    const double error = m_cellError[i];
    ++block.covered;
    block.sumSquares += error * error;
    block.maxError = std::max(block.maxError, error);
    if (squaredError != nullptr)
        *squaredError = corner ? 0.0 : error * error;
    if (m_maxError && error > *m_maxError && insertable())
        block.proposals.push_back(asCandidate(error));
}

void CompletionCheck::propose(const CellToInsert& candidate, CompletionMeasure& measure) {
    std::uint32_t& slot = m_candidateOf[candidate.triangle];
    if (slot == kNoCandidate) {
        slot = static_cast<std::uint32_t>(measure.candidates.size());
        measure.candidates.push_back(candidate);
    } else if (candidate.priority > measure.candidates[slot].priority) {
        measure.candidates[slot] = candidate;
    }
}

} // namespace terratin::detail

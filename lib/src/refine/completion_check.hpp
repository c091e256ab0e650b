#pragma once
/// @file
/// The check of a constrained TIN against the grid that completeWithCells (cell_completion.hpp)
/// repeats after each round of insertions: every cell is located once, and after that only the
/// cells of the triangles the insertions changed (the others hold the same cells with the same
/// errors). The cells are checked in fixed blocks on the threads, so the result is the same for
/// any number of them.

#include "cell_completion.hpp"
#include "located_check.hpp"

#include "../parallel/parallel_for.hpp"

#include "terratin/constrain/constrained_tin.hpp"
#include "terratin/geometry/height_grid.hpp"
#include "terratin/geometry/point.hpp"
#include "terratin/triangulate/tin_locator.hpp"

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

namespace terratin::detail {

/// The triangle of a cell outside the TIN's hull: none.
inline constexpr std::uint32_t kOutsideHull = 0xffffffffU;

/// One check of the whole constrained TIN.
struct CompletionMeasure {
    double maxError = 0.0;
    double sumSquares = 0.0;
    std::size_t covered = 0;
    std::size_t uncovered = 0;
    /// The triangles dropped (outside the area, or over an open hole); only from a measure of
    /// every cell.
    std::vector<std::uint8_t> drop;
    /// 1 for the triangles dropped only for covering an open hole's cell (holeTriangles); only
    /// from a measure of every cell.
    std::vector<std::uint8_t> overHoleOnly;
    std::size_t holeTriangles = 0;
    /// At most one per triangle: its worst cell over the bound (kHolePriority: a valid cell in a
    /// triangle over an open hole), in the refiner's terms.
    std::vector<CellToInsert> candidates;
};

class CompletionCheck {
public:
    CompletionCheck(const HeightGrid& grid, std::span<const Point2> positions,
                    const ConstrainedTin& tin, const CompletionRules& rules,
                    std::optional<double> maxError, unsigned threads);

    /// Measures the TIN; `changed` (empty: everything) marks the triangles changed since the
    /// last call. With `everyCell` false, only the cells located again (those of changed
    /// triangles) are measured and counted: the candidates then come from changed triangles
    /// alone, where the last insertions left them. `squaredErrors`, when given, receives each
    /// measured cell's squared error (NaN: in no kept triangle); only with `everyCell`.
    [[nodiscard]] CompletionMeasure measure(const std::vector<std::uint8_t>& changed,
                                            bool everyCell,
                                            std::vector<double>* squaredErrors = nullptr);

private:
    /// What the check of a block of cells found: the figures, and every cell proposed as its
    /// triangle's candidate, in cell order.
    struct BlockTally {
        double maxError = 0.0;
        double sumSquares = 0.0;
        std::size_t covered = 0;
        std::size_t uncovered = 0;
        std::vector<CellToInsert> proposals;
    };

    /// The cells are checked in fixed blocks of this many on the threads: the blocks, not the
    /// threads, decide the order of the walks and of the sums, so the result is the same for
    /// any number of threads.
    static constexpr std::size_t kCellBlock = 16384;

    /// What keeps a cell in triangle t from being measured there, as bits: outside the area,
    /// flat (a replace area) or over an open hole.
    static constexpr std::uint8_t kDropped = 1;
    static constexpr std::uint8_t kFlat = 2;
    static constexpr std::uint8_t kOverHole = 4;

    /// m_left: per triangle, its kDropped, kFlat (the rules' answers) and kOverHole bits in one
    /// byte, so that a cell's tally reads one byte of its triangle instead of three arrays.
    /// Returns the count of triangles over an open hole that the area keeps (they are dropped
    /// too). Only the rules need a pass over every triangle (on the threads): the late checks
    /// locate a few hundred cells, and without rules they touch only the hole marks.
    std::size_t markTrianglesLeftOut();
    /// The kDropped and kFlat bits of every triangle, from the rules.
    void markRulesLeftOut();
    /// The kOverHole bit of the triangles holding an open hole's cell (a closed triangle covers
    /// a cell on its edge too, so both sides of such an edge count), each listed once in
    /// m_overHoleMarked, so that the next check clears them one by one: there are few, against
    /// a pass over every triangle. Returns how many of them the area keeps.
    std::size_t markTrianglesOverHoles();
    /// measure.drop: the triangles outside the area or over an open hole; and
    /// measure.overHoleOnly: those over an open hole that the area keeps. From m_left, on the
    /// threads.
    void dropTriangles(CompletionMeasure& measure) const;
    /// Counts measured cell i into `block`, and proposes it as its triangle's candidate when it
    /// is over the bound, or lies in a triangle over an open hole, and may be inserted.
    void tally(std::size_t i, BlockTally& block, double* squaredError) const;
    /// `candidate` becomes its triangle's candidate unless that has a worse one (an earlier
    /// cell keeps a tie).
    void propose(const CellToInsert& candidate, CompletionMeasure& measure);

    /// Locates again the cells (measured ones, and open holes' ones) of changed triangles; the
    /// measured ones are listed in m_relocated, in cell order (on the first check, every cell:
    /// m_relocatedAll, no list).
    void relocate(const std::vector<std::uint8_t>& changed);
    /// The first check: each measured cell that is not a vertex walks from the triangle of the
    /// cell before it; each block with a fresh copy of the locator, made when the block first
    /// needs one.
    void locateEveryCell();
    /// A later check: the measured cells of changed triangles walk from their old triangle,
    /// and are listed in m_relocated.
    void relocateCellsOf(const std::vector<std::uint8_t>& changed);
    /// Locates again the open holes' cells of changed triangles, in blocks on the threads as
    /// the measured cells; each walks from its old triangle, or on the first check from the
    /// locator's start near it.
    void relocateHoleCells(const std::vector<std::uint8_t>& changed);
    /// Gives each measured cell that is a vertex of the TIN (at the cell's position) the
    /// lowest-numbered triangle around it, and its error there: the vertex's own elevation
    /// against the cell's. A simplified TIN has most of its cells as vertices, and a vertex
    /// needs no walk. On the threads; the lowest triangle makes the result the same for any
    /// number of them.
    void placeVertexCells();
    /// Locates measured cell i, walking from triangle `start` (kOutsideHull: from where the
    /// locator's last walk ended), and measures its error there.
    void measureAt(std::size_t i, TinLocator& locator, std::uint32_t start);

    [[nodiscard]] Point2 position(std::size_t cell) const {
        return cellPosition(*m_grid, m_positions, cell);
    }
    /// Whether a cell in triangle `t` must be located again. A cell outside the hull
    /// (kOutsideHull) stays outside: the insertions keep the hull.
    static bool stale(std::uint32_t t, const std::vector<std::uint8_t>& changed) {
        return changed.empty() || (t != kOutsideHull && changed[t] != 0);
    }
    /// Calls visit(block, begin, end) for the fixed blocks of kCellBlock of [0, count), the
    /// threads taking them in turn. Plain threads, joined before it returns (parallelForChunks,
    /// as the triangulators' loops): ThreadSanitizer sees what they write, which it cannot
    /// through an uninstrumented task pool.
    template <class Visit> void forEachBlock(std::size_t count, Visit&& visit) const {
        parallelForChunks(count, m_threads, kCellBlock,
                          [&](unsigned, std::size_t begin, std::size_t end) {
                              visit(begin / kCellBlock, begin, end);
                          });
    }

    const HeightGrid* m_grid;
    std::span<const Point2> m_positions;
    const ConstrainedTin* m_tin;
    const CompletionRules* m_rules;
    std::optional<double> m_maxError;
    unsigned m_threads;
    /// For each measured cell the triangle holding it (kOutsideHull: outside the hull) and its
    /// error there; the triangle holding each open hole cell.
    std::vector<std::uint32_t> m_cellTriangle;
    std::vector<double> m_cellError;
    /// 1 for a measured cell at a corner of its triangle (a vertex).
    std::vector<std::uint8_t> m_cellAtCorner;
    std::vector<std::uint32_t> m_holeTriangle;
    std::vector<std::size_t> m_relocated;
    bool m_relocatedAll = false;
    /// Built on the first measure (TinLocator::locateNearFrom may follow insertions).
    std::optional<TinLocator> m_locator;
    /// Per triangle, what keeps its cells from being measured (markTrianglesLeftOut), kept
    /// from one check to the next: fresh memory costs a page fault per 4 KiB written. The
    /// triangles whose kOverHole bit is set, to clear them.
    std::vector<std::uint8_t> m_left;
    std::vector<std::uint32_t> m_overHoleMarked;
    /// Per triangle, its candidate's place in CompletionMeasure::candidates while a measure
    /// runs (kNoCandidate: none yet).
    static constexpr std::uint32_t kNoCandidate = 0xffffffffU;
    std::vector<std::uint32_t> m_candidateOf;
};

} // namespace terratin::detail

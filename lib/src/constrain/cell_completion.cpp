#include "cell_completion.hpp"

#include "../parallel/parallel_for.hpp"
#include "terratin/constrain/insert_constraints.hpp"
#include "terratin/error.hpp"
#include "terratin/geometry/predicates.hpp"
#include "terratin/triangulate/tin_locator.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

namespace terratin::detail {

namespace {

/// Whether p lies on the line of edge i of triangle t, up to rounding (within the error bound
/// of orient2d's floating-point stage, as TinLocator::locateNear decides).
bool onEdgeLine(const TinMesh& mesh, std::size_t t, std::size_t i, Point2 p) {
    const Point3& a = mesh.vertices[mesh.triangles[3 * t + i]];
    const Point3& b = mesh.vertices[mesh.triangles[3 * t + (i + 1) % 3]];
    const double detLeft = (a.x - p.x) * (b.y - p.y);
    const double detRight = (a.y - p.y) * (b.x - p.x);
    return std::fabs(detLeft - detRight) <=
           predicates::detail::kOrient2dErrorBoundA * (std::fabs(detLeft) + std::fabs(detRight));
}

/// The triangle across the edge of triangle t that p lies on, or kNoNeighbour when p lies on
/// none or that edge is on the hull. The first such edge.
std::int32_t neighbourSharing(const TinMesh& mesh, std::size_t t, Point2 p) {
    for (std::size_t i = 0; i < 3; ++i)
        if (onEdgeLine(mesh, t, i, p))
            return mesh.neighbours[3 * t + i];
    return kNoNeighbour;
}

/// The corner of triangle t at p (0 to 2), or 3 when none is.
std::size_t cornerAt(const TinMesh& mesh, std::size_t t, Point2 p) {
    for (std::size_t i = 0; i < 3; ++i) {
        const Point3& corner = mesh.vertices[mesh.triangles[3 * t + i]];
        if (corner.x == p.x && corner.y == p.y)
            return i;
    }
    return 3;
}

bool isCorner(const TinMesh& mesh, std::size_t t, Point2 p) {
    return cornerAt(mesh, t, p) < 3;
}

/// A triangle that `kept` accepts and that holds p on its boundary, found from triangle t
/// (which holds p): around p's vertex when p is a corner of t, else across an edge p lies on;
/// kNoNeighbour when none does. Slivers whose corners all lie near one line (a constrained
/// boundary's pockets) hold p near several edges' lines: every such edge is tried.
template <class Kept>
std::int32_t keptTriangleAt(const TinMesh& mesh, std::size_t t, Point2 p, const Kept& kept) {
    const std::size_t corner = cornerAt(mesh, t, p);
    if (corner == 3) {
        for (std::size_t i = 0; i < 3; ++i) {
            const std::int32_t n = mesh.neighbours[3 * t + i];
            if (n != kNoNeighbour && kept(static_cast<std::size_t>(n)) && onEdgeLine(mesh, t, i, p))
                return n;
        }
        return kNoNeighbour;
    }
    // Around the vertex, one way and then the other, until a kept triangle or the hull.
    const std::uint32_t vertex = mesh.triangles[3 * t + corner];
    for (const std::size_t turn : {std::size_t{0}, std::size_t{2}}) {
        std::int32_t u = static_cast<std::int32_t>(t);
        for (;;) {
            const auto at = static_cast<std::size_t>(u);
            std::size_t i = 0;
            while (mesh.triangles[3 * at + i] != vertex)
                ++i;
            u = mesh.neighbours[3 * at + (i + turn) % 3];
            if (u == kNoNeighbour || u == static_cast<std::int32_t>(t))
                break;
            if (kept(static_cast<std::size_t>(u)))
                return u;
        }
    }
    return kNoNeighbour;
}

/// The plane of triangle t at p (barycentric, in double).
double planeAt(const TinMesh& mesh, std::size_t t, Point2 p) {
    const Point3& a = mesh.vertices[mesh.triangles[3 * t]];
    const Point3& b = mesh.vertices[mesh.triangles[3 * t + 1]];
    const Point3& c = mesh.vertices[mesh.triangles[3 * t + 2]];
    const double area = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
    const double wb = ((p.x - a.x) * (c.y - a.y) - (p.y - a.y) * (c.x - a.x)) / area;
    const double wc = ((b.x - a.x) * (p.y - a.y) - (b.y - a.y) * (p.x - a.x)) / area;
    return a.z + wb * (b.z - a.z) + wc * (c.z - a.z);
}

/// A triangle's cell to insert: the worst over the bound (error infinite: a valid cell in a
/// triangle over an open hole).
struct Candidate {
    double error = 0.0;
    std::size_t cell = 0;
    std::uint32_t triangle = 0;
};

/// What the check of a block of cells found: the figures, and every cell proposed as its
/// triangle's candidate, in cell order.
struct BlockTally {
    double maxError = 0.0;
    double sumSquares = 0.0;
    std::size_t covered = 0;
    std::size_t uncovered = 0;
    std::vector<Candidate> proposals;
};

/// One check of the whole constrained TIN.
struct Measure {
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
    std::vector<Candidate> candidates; // at most one per triangle
};

constexpr std::uint32_t kNoTriangle = 0xffffffffU;

/// The cells are checked in fixed blocks of this many on the threads: the blocks, not the
/// threads, decide the order of the walks and of the sums, so the result is the same for any
/// number of threads.
constexpr std::size_t kCellBlock = 16384;

/// Measures the constrained TIN against the grid, again after each round of insertions: every
/// cell is located once, and after that only the cells of the triangles the insertions changed
/// (the others hold the same cells with the same errors).
class CompletionCheck {
public:
    CompletionCheck(const HeightGrid& grid, std::span<const Point2> positions,
                    const ConstrainedTin& tin, const CompletionRules& rules,
                    std::optional<double> maxError, unsigned threads)
        : m_grid(&grid), m_positions(positions), m_tin(&tin), m_rules(&rules), m_maxError(maxError),
          m_threads(std::max(threads, 1U)) {
        m_cellTriangle.assign(rules.measuredCells.size(), kNoTriangle);
        m_cellError.assign(rules.measuredCells.size(), 0.0);
        m_cellAtCorner.assign(rules.measuredCells.size(), 0);
        m_holeTriangle.assign(rules.openHoleCells.size(), kNoTriangle);
    }

    /// Measures the TIN; `changed` (empty: everything) marks the triangles changed since the
    /// last call. With `everyCell` false, only the cells located again (those of changed
    /// triangles) are measured and counted: the candidates then come from changed triangles
    /// alone, where the last insertions left them. `squaredErrors`, when given, receives each
    /// measured cell's squared error (NaN: in no kept triangle); only with `everyCell`.
    [[nodiscard]] Measure measure(const std::vector<std::uint8_t>& changed, bool everyCell,
                                  std::vector<double>* squaredErrors = nullptr) {
        relocate(changed);
        const std::size_t triangles = m_tin->mesh.triangleCount();
        Measure measure;
        measure.holeTriangles = markTrianglesLeftOut();
        m_candidateOf.resize(triangles, kNoTriangle);
        // The first check locates every cell: they are all measured, as with everyCell.
        const bool allCells = everyCell || m_relocatedAll;
        const std::size_t count = allCells ? m_rules->measuredCells.size() : m_relocated.size();
        if (squaredErrors != nullptr)
            squaredErrors->assign(count, std::numeric_limits<double>::quiet_NaN());
        std::vector<BlockTally> blocks((count + kCellBlock - 1) / kCellBlock);
        forEachBlock(count, [&](std::size_t block, std::size_t begin, std::size_t end) {
            for (std::size_t k = begin; k < end; ++k) {
                const std::size_t i = allCells ? k : m_relocated[k];
                tally(i, m_left, blocks[block],
                      squaredErrors != nullptr ? &(*squaredErrors)[i] : nullptr);
            }
        });
        for (const BlockTally& block : blocks) {
            measure.maxError = std::max(measure.maxError, block.maxError);
            measure.sumSquares += block.sumSquares;
            measure.covered += block.covered;
            measure.uncovered += block.uncovered;
            for (const Candidate& candidate : block.proposals)
                propose(candidate, measure);
        }
        for (const Candidate& candidate : measure.candidates)
            m_candidateOf[candidate.triangle] = kNoTriangle;
        if (everyCell)
            dropTriangles(measure);
        return measure;
    }

private:
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
    std::size_t markTrianglesLeftOut() {
        for (const std::uint32_t t : m_overHoleMarked)
            if (t < m_left.size())
                m_left[t] &= static_cast<std::uint8_t>(~kOverHole);
        m_overHoleMarked.clear();
        m_left.resize(m_tin->mesh.triangleCount(), 0);
        if (m_rules->outsideArea || m_rules->unmeasured)
            markRulesLeftOut();
        return markTrianglesOverHoles();
    }

    /// The kDropped and kFlat bits of every triangle, from the rules.
    void markRulesLeftOut() {
        const std::vector<std::uint8_t> outside =
            m_rules->outsideArea ? m_rules->outsideArea(*m_tin) : std::vector<std::uint8_t>{};
        const std::vector<std::uint8_t> flat =
            m_rules->unmeasured ? m_rules->unmeasured(*m_tin) : std::vector<std::uint8_t>{};
        parallelFor(m_left.size(), m_threads, [&](unsigned, std::size_t begin, std::size_t end) {
            for (std::size_t t = begin; t < end; ++t) {
                const bool dropped = !outside.empty() && outside[t] != 0;
                const bool isFlat = !flat.empty() && flat[t] != 0;
                m_left[t] =
                    static_cast<std::uint8_t>((dropped ? kDropped : 0) | (isFlat ? kFlat : 0));
            }
        });
    }

    /// measure.drop: the triangles outside the area or over an open hole; and
    /// measure.overHoleOnly: those over an open hole that the area keeps. From m_left, on the
    /// threads.
    void dropTriangles(Measure& measure) const {
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

    [[nodiscard]] Point2 position(std::size_t cell) const {
        return cellPosition(*m_grid, m_positions, cell);
    }

    /// The kOverHole bit of the triangles holding an open hole's cell (a closed triangle covers
    /// a cell on its edge too, so both sides of such an edge count), each listed once in
    /// m_overHoleMarked, so that the next check clears them one by one: there are few, against
    /// a pass over every triangle. Returns how many of them the area keeps.
    std::size_t markTrianglesOverHoles() {
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
            if (t == kNoTriangle)
                continue;
            mark(t);
            const std::int32_t other =
                neighbourSharing(mesh, t, position(m_rules->openHoleCells[i]));
            if (other != kNoNeighbour)
                mark(static_cast<std::size_t>(other));
        }
        return keptByTheArea;
    }

    /// Whether a cell in triangle `t` must be located again. A cell outside the hull
    /// (kNoTriangle) stays outside: the insertions keep the hull.
    static bool stale(std::uint32_t t, const std::vector<std::uint8_t>& changed) {
        return changed.empty() || (t != kNoTriangle && changed[t] != 0);
    }

    /// Calls visit(block, begin, end) for the fixed blocks of kCellBlock of [0, count), the
    /// threads taking them in turn. Plain threads, joined before it returns (parallelForChunks,
    /// as the triangulators' loops): ThreadSanitizer sees what they write, which it cannot
    /// through an uninstrumented task pool.
    template <class Visit> void forEachBlock(std::size_t count, Visit&& visit) {
        parallelForChunks(count, m_threads, kCellBlock,
                          [&](unsigned, std::size_t begin, std::size_t end) {
                              visit(begin / kCellBlock, begin, end);
                          });
    }

    /// Locates again the cells (measured ones, and open holes' ones) of changed triangles; the
    /// measured ones are listed in m_relocated, in cell order (on the first check, every cell:
    /// m_relocatedAll, no list).
    void relocate(const std::vector<std::uint8_t>& changed) {
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

    /// The first check: each measured cell that is not a vertex walks from the triangle of the
    /// cell before it; each block with a fresh copy of the locator, made when the block first
    /// needs one.
    void locateEveryCell() {
        forEachBlock(m_rules->measuredCells.size(),
                     [&](std::size_t, std::size_t begin, std::size_t end) {
                         std::optional<TinLocator> blockLocator;
                         std::uint32_t previous = kNoTriangle;
                         for (std::size_t i = begin; i < end; ++i) {
                             if (m_cellTriangle[i] == kNoTriangle) {
                                 if (!blockLocator)
                                     blockLocator.emplace(*m_locator);
                                 measureAt(i, *blockLocator, previous);
                             }
                             if (m_cellTriangle[i] != kNoTriangle)
                                 previous = m_cellTriangle[i];
                         }
                     });
        m_relocated.clear();
        m_relocatedAll = true;
    }

    /// A later check: the measured cells of changed triangles walk from their old triangle,
    /// and are listed in m_relocated.
    void relocateCellsOf(const std::vector<std::uint8_t>& changed) {
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

    /// Locates again the open holes' cells of changed triangles, in blocks on the threads as
    /// the measured cells; each walks from its old triangle, or on the first check from the
    /// locator's start near it.
    void relocateHoleCells(const std::vector<std::uint8_t>& changed) {
        const std::vector<std::size_t>& cells = m_rules->openHoleCells;
        forEachBlock(cells.size(), [&](std::size_t, std::size_t begin, std::size_t end) {
            std::optional<TinLocator> blockLocator;
            for (std::size_t i = begin; i < end; ++i) {
                if (!stale(m_holeTriangle[i], changed))
                    continue;
                if (!blockLocator)
                    blockLocator.emplace(*m_locator);
                m_holeTriangle[i] =
                    blockLocator->locateNearFrom(position(cells[i]), m_holeTriangle[i])
                        .value_or(kNoTriangle);
            }
        });
    }

    /// Gives each measured cell that is a vertex of the TIN (at the cell's position) the
    /// lowest-numbered triangle around it, and its error there: the vertex's own elevation
    /// against the cell's. A simplified TIN has most of its cells as vertices, and a vertex
    /// needs no walk. On the threads; the lowest triangle makes the result the same for any
    /// number of them.
    void placeVertexCells() {
        constexpr std::uint32_t kNotMeasured = 0xffffffffU;
        const std::vector<std::size_t>& cells = m_rules->measuredCells;
        std::vector<std::uint32_t> measuredIndex(m_grid->cellCount(), kNotMeasured);
        parallelFor(cells.size(), m_threads, [&](unsigned, std::size_t begin, std::size_t end) {
            for (std::size_t i = begin; i < end; ++i) // distinct cells
                measuredIndex[cells[i]] = static_cast<std::uint32_t>(i);
        });
        const TinMesh& mesh = m_tin->mesh;
        std::vector<std::uint32_t> vertexTriangle(mesh.vertexCount(), kNoTriangle);
        // Downwards, so that the lowest triangle writes last: on one thread, where an atomic
        // minimum per corner on the threads is slower (docs/benchmarks.md).
        for (std::size_t t = mesh.triangleCount(); t-- > 0;)
            for (std::size_t k = 0; k < 3; ++k)
                vertexTriangle[mesh.triangles[3 * t + k]] = static_cast<std::uint32_t>(t);
        parallelFor(mesh.vertexCount(), m_threads,
                    [&](unsigned, std::size_t begin, std::size_t end) {
                        for (std::size_t v = begin; v < end; ++v) {
                            const std::uint32_t cell = mesh.sourceIndex[v];
                            if (cell >= measuredIndex.size() || measuredIndex[cell] == kNotMeasured)
                                continue;
                            const Point3& at = mesh.vertices[v];
                            const Point2 p = position(cell);
                            if (at.x != p.x || at.y != p.y)
                                continue;
                            // Only this vertex lies at the cell's position: no other thread
                            // writes cell i.
                            const std::uint32_t i = measuredIndex[cell];
                            m_cellTriangle[i] = vertexTriangle[v];
                            m_cellError[i] = std::abs(double{m_grid->z[cell]} - at.z);
                            m_cellAtCorner[i] = 1;
                        }
                    });
    }

    /// Locates measured cell i, walking from triangle `start` (kNoTriangle: from where the
    /// locator's last walk ended), and measures its error there.
    void measureAt(std::size_t i, TinLocator& locator, std::uint32_t start) {
        const std::size_t cell = m_rules->measuredCells[i];
        const Point2 p = position(cell);
        const std::uint32_t t = locator.locateNearFrom(p, start).value_or(kNoTriangle);
        m_cellTriangle[i] = t;
        if (t == kNoTriangle)
            return;
        // Measured while the walk has the triangle's corners in cache: the tally, a pass
        // over every cell later, then reads no corner.
        m_cellError[i] = std::abs(double{m_grid->z[cell]} - planeAt(m_tin->mesh, t, p));
        m_cellAtCorner[i] = isCorner(m_tin->mesh, t, p) ? 1 : 0;
    }

    /// Counts measured cell i into `block`, and proposes it as its triangle's candidate when it
    /// is over the bound, or lies in a triangle over an open hole, and may be inserted. `left`:
    /// markTrianglesLeftOut.
    void tally(std::size_t i, const std::vector<std::uint8_t>& left, BlockTally& block,
               double* squaredError) const {
        std::uint32_t t = m_cellTriangle[i];
        if (t == kNoTriangle) {
            ++block.uncovered;
            return;
        }
        const std::size_t cell = m_rules->measuredCells[i];
        bool corner = m_cellAtCorner[i] != 0;
        if (left[t] != 0) {
            // A cell on an edge or at a vertex belongs to a kept triangle beside, if there is
            // one (its error there is the same: the planes meet along the edge).
            const std::int32_t other = keptTriangleAt(m_tin->mesh, t, position(cell),
                                                      [&](std::size_t u) { return left[u] == 0; });
            if (other != kNoNeighbour) {
                t = static_cast<std::uint32_t>(other);
                corner = isCorner(m_tin->mesh, t, position(cell));
            }
        }
        if ((left[t] & (kDropped | kFlat)) != 0)
            return; // outside the output's area, or in a replace area
        // Asked only of a cell about to be proposed: the rule may be a call per cell.
        const auto insertable = [&] {
            return !corner && (!m_rules->insertable || m_rules->insertable(cell));
        };
        if ((left[t] & kOverHole) != 0 && !corner) {
            // As the refiner does: a hole's triangle is split until it covers no valid cell.
            ++block.uncovered;
            if (insertable())
                block.proposals.push_back({std::numeric_limits<double>::infinity(), cell, t});
            return;
        }
        const double error = m_cellError[i];
        ++block.covered;
        block.sumSquares += error * error;
        block.maxError = std::max(block.maxError, error);
        if (squaredError != nullptr)
            *squaredError = corner ? 0.0 : error * error;
        if (m_maxError && error > *m_maxError && insertable())
            block.proposals.push_back({error, cell, t});
    }

    /// `candidate` becomes its triangle's candidate unless that has a worse one (an earlier
    /// cell keeps a tie).
    void propose(const Candidate& candidate, Measure& measure) {
        std::uint32_t& slot = m_candidateOf[candidate.triangle];
        if (slot == kNoTriangle) {
            slot = static_cast<std::uint32_t>(measure.candidates.size());
            measure.candidates.push_back(candidate);
        } else if (candidate.error > measure.candidates[slot].error) {
            measure.candidates[slot] = candidate;
        }
    }

    const HeightGrid* m_grid;
    std::span<const Point2> m_positions;
    const ConstrainedTin* m_tin;
    const CompletionRules* m_rules;
    std::optional<double> m_maxError;
    unsigned m_threads;
    /// For each measured cell the triangle holding it (kNoTriangle: outside the hull) and its
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
    /// Per triangle, its candidate's place in Measure::candidates while a measure runs.
    std::vector<std::uint32_t> m_candidateOf;
};

/// The candidates to insert, worst first when a limit cuts them, then in cell order (short
/// walks); empty when a limit leaves no room (`limitReached` set).
std::vector<Candidate> chooseCandidates(std::vector<Candidate> worst, const TinMesh& mesh,
                                        const RefineOptions& options, bool& limitReached) {
    std::size_t room = worst.size();
    if (options.maxPoints)
        room = std::min(room, *options.maxPoints > mesh.vertexCount()
                                  ? *options.maxPoints - mesh.vertexCount()
                                  : std::size_t{0});
    if (options.maxTriangles) // each inserted point adds two triangles
        room = std::min(room, *options.maxTriangles > mesh.triangleCount() + 1
                                  ? (*options.maxTriangles - mesh.triangleCount()) / 2
                                  : std::size_t{0});
    if (room < worst.size()) {
        limitReached = true;
        std::sort(worst.begin(), worst.end(), [](const Candidate& a, const Candidate& b) {
            return a.error != b.error ? a.error > b.error : a.cell < b.cell;
        });
        worst.resize(room);
    }
    std::sort(worst.begin(), worst.end(),
              [](const Candidate& a, const Candidate& b) { return a.cell < b.cell; });
    return worst;
}

/// The valid cells beside the vertices that only triangles over open holes use (each such
/// vertex would drop out of the TIN with them, leaving its cell uncovered): the cells around
/// each, not vertices and insertable, as candidates to insert at the holes' priority. As
/// stranded_cells.hpp does for the refiner.
std::vector<Candidate> cellsBesideStrandedVertices(const HeightGrid& grid, const TinMesh& mesh,
                                                   const Measure& measure,
                                                   const CompletionRules& rules) {
    constexpr std::uint8_t kKept = 1;
    constexpr std::uint8_t kOverHole = 2;
    std::vector<std::uint8_t> uses(mesh.vertexCount(), 0);
    std::vector<std::uint32_t> triangleOf(mesh.vertexCount(), kNoTriangle);
    for (std::size_t t = 0; t < mesh.triangleCount(); ++t)
        for (std::size_t i = 0; i < 3; ++i) {
            const std::uint32_t v = mesh.triangles[3 * t + i];
            if (measure.drop[t] == 0)
                uses[v] |= kKept;
            else if (measure.overHoleOnly[t] != 0)
                uses[v] |= kOverHole;
            triangleOf[v] = static_cast<std::uint32_t>(t);
        }
    std::vector<std::uint8_t> isVertex(grid.cellCount(), 0);
    for (const std::uint32_t cell : mesh.sourceIndex)
        if (cell < grid.cellCount())
            isVertex[cell] = 1;
    std::vector<Candidate> candidates;
    const auto width = static_cast<std::int64_t>(grid.width);
    const auto height = static_cast<std::int64_t>(grid.height);
    for (std::size_t v = 0; v < mesh.vertexCount(); ++v) {
        const std::uint32_t cell = mesh.sourceIndex[v];
        if (uses[v] != kOverHole || cell >= grid.cellCount())
            continue;
        const std::int64_t row = cell / width;
        const std::int64_t column = cell % width;
        for (std::int64_t r = std::max<std::int64_t>(row - 1, 0);
             r <= std::min(row + 1, height - 1); ++r)
            for (std::int64_t c = std::max<std::int64_t>(column - 1, 0);
                 c <= std::min(column + 1, width - 1); ++c) {
                const auto neighbour = static_cast<std::size_t>(r * width + c);
                if (grid.isValid(neighbour) && isVertex[neighbour] == 0 &&
                    (!rules.insertable || rules.insertable(neighbour))) {
                    isVertex[neighbour] = 1; // once
                    candidates.push_back(
                        {std::numeric_limits<double>::infinity(), neighbour, triangleOf[v]});
                }
            }
    }
    std::sort(candidates.begin(), candidates.end(),
              [](const Candidate& a, const Candidate& b) { return a.cell < b.cell; });
    return candidates;
}

} // namespace

Completion completeWithCells(const HeightGrid& grid, std::span<const Point2> positions,
                             ConstrainedTin& tin, const CompletionRules& rules,
                             const RefineOptions& options, unsigned threads,
                             const ProgressCallback& progress) {
    Completion result;
    CompletionCheck check(grid, positions, tin, rules, options.maxError, threads);
    std::vector<std::uint8_t> changed; // empty: every triangle is new to the check
    bool everyCell = false;
    Measure measure;
    const auto finalMeasure = [&] {
        return check.measure(changed, true, rules.keepCellErrors ? &result.squaredErrors : nullptr);
    };
    for (;;) {
        if (progress && !progress(1.0 - 1.0 / static_cast<double>(result.passes + 1),
                                  "inserting cells over the bound"))
            throw Cancelled("Constrained refiner: cancelled");
        measure = everyCell ? finalMeasure() : check.measure(changed, false);
        ++result.passes;
        std::vector<Candidate> candidates =
            chooseCandidates(std::move(measure.candidates), tin.mesh, options, result.limitReached);
        if (candidates.empty() && everyCell && rules.coverStrandedVertices && !result.limitReached)
            candidates =
                chooseCandidates(cellsBesideStrandedVertices(grid, tin.mesh, measure, rules),
                                 tin.mesh, options, result.limitReached);
        if (candidates.empty()) {
            if (everyCell)
                break;
            // The changed triangles are within the bound: every cell is measured, for the
            // figures and to make sure.
            everyCell = true;
            changed.assign(tin.mesh.triangleCount(), 0);
            continue;
        }
        everyCell = false;
        std::vector<Point3> points;
        std::vector<std::uint32_t> cells; // each point's source index
        std::vector<std::uint32_t> near;  // where each was located: its walk starts there
        for (const Candidate& candidate : candidates) {
            const Point2 p = cellPosition(grid, positions, candidate.cell);
            points.push_back({p.x, p.y, double{grid.z[candidate.cell]}});
            cells.push_back(static_cast<std::uint32_t>(candidate.cell));
            near.push_back(candidate.triangle);
        }
        const std::size_t inserted = insertVertices(tin, points, cells, &changed, near, threads);
        if (rules.afterInsertions)
            rules.afterInsertions(tin);
        result.insertedCells += inserted;
        if (inserted == 0) {
            measure = finalMeasure();
            break;
        }
    }
    result.maxError = measure.maxError;
    result.sumSquares = measure.sumSquares;
    result.rmse = measure.covered > 0
                      ? std::sqrt(measure.sumSquares / static_cast<double>(measure.covered))
                      : 0.0;
    result.coveredCells = measure.covered;
    result.uncoveredCells = measure.uncovered;
    result.holeTriangles = measure.holeTriangles;
    result.drop = std::move(measure.drop);
    return result;
}

} // namespace terratin::detail

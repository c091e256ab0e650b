#pragma once
/// @file
/// The greedy insertion loop (Garland & Heckbert's "greedy insertion" with a priority queue of
/// per-triangle candidates), run in vertical strips of the raster at once. The whole story
/// (strips, pairs of strips, the shared step, levels of error) is in docs/algorithms.md, "The
/// refiner"; level_schedule.hpp and level_tasks.hpp hold the levels and a level's tasks.
///
/// What a caller relies on: the TIN is the same for any number of threads (a task's
/// insertions depend only on its own triangles); greedy order holds within a task, and across
/// tasks within a level, which costs a fraction of a percent of points.
///
/// Candidates are lazy: one is stale when its triangle's slot changed since (RefineMesh
/// versions) or its cell became a vertex.
///
/// Priorities: a triangle covering an open hole's cell and a valid non-vertex cell is
/// refined before any error (kHolePriority), so the triangles finally dropped over holes hold
/// no valid cell that another triangle would not cover; otherwise the priority is the largest
/// error, and only errors above the target become candidates. Ties: the lowest cell index.
///
/// Limits (points, triangles) give each task a share of what is left per level; when little
/// is left, one thread finishes in global priority order and stops exactly at the limit.

#include "../parallel/round_workers.hpp"
#include "candidate_queue.hpp"
#include "cell_flags.hpp"
#include "grid_scan.hpp"
#include "located_check.hpp"
#include "triangle_scan.hpp"

#include "refine_mesh.hpp"

#include "terratin/progress.hpp"
#include "terratin/refine/refine.hpp"

#include <atomic>
#include <cstdint>
#include <cstdlib>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace terratin::detail {

class GreedyRefiner {
public:
    /// `flags` from makeCellFlags; the refiner marks vertices in it. `positions`: where each
    /// cell lies in the TIN (refine's positions), or empty for the grid's cell centres.
    GreedyRefiner(const HeightGrid& grid, std::span<const Point2> positions, CellFlags& flags,
                  const RefineOptions& options, RoundWorkers& workers);

    /// Cells to make vertices right after the hull, before any candidate is chosen (a tile's
    /// border vertices, tile_refine.hpp): valid cells inside or on the hull. Call before run().
    void setSeedCells(std::vector<std::uint32_t> cells) { m_seedCells = std::move(cells); }

    /// Runs to the target or a limit. Throws Cancelled when `progress` returns false.
    void run(const ProgressCallback& progress);

    /// The Delaunay triangulation of the chosen cells as a TinMesh (vertices at the cells'
    /// positions, sourceIndex = cell index) in raster order (cell_order.hpp); with
    /// `slotOfTriangle`, also the mesh slot of each of its triangles; with room for
    /// `spareVertices` more vertices (reserveRoom).
    [[nodiscard]] TinMesh extractInCellOrder(std::vector<TriId>* slotOfTriangle = nullptr,
                                             std::size_t spareVertices = 0) const;

    /// After run(), with `mesh` its last extractInCellOrder(&slots, spareVertices): while a
    /// vertex is used only by triangles over open holes, inserts its neighbours
    /// (stranded_cells.hpp), refines on, and extracts `mesh` and `slots` again, each time a
    /// completion pass; not after a limit stopped the refinement. Returns the final mesh's
    /// trianglesOverOpenHoles, empty when the grid has no open hole.
    std::vector<std::uint8_t> coverStrandedVertices(TinMesh& mesh, std::vector<TriId>& slots,
                                                    std::size_t spareVertices,
                                                    const ProgressCallback& progress);

    [[nodiscard]] RefineStop stop() const { return m_stop; }
    [[nodiscard]] std::size_t hullPoints() const { return m_hullPoints; }
    [[nodiscard]] std::size_t strips() const { return m_strips.size(); }
    [[nodiscard]] std::size_t levels() const { return m_levels; }
    /// Candidates a strip or a pair refused because their insertion reached past it.
    [[nodiscard]] std::size_t deferred() const { return m_deferred; }
    /// Points inserted by the pairs of strips, and by the sequential step of the levels.
    [[nodiscard]] std::size_t pairInsertions() const { return m_pairInsertions; }
    [[nodiscard]] std::size_t sharedInsertions() const { return m_sharedInsertions; }
    /// Completion passes: of completeAtPositions, and of coverStrandedVertices.
    [[nodiscard]] std::size_t completionPasses() const { return m_completionPasses; }
    [[nodiscard]] std::size_t meshBytes() const { return m_mesh->memoryBytes(); }

private:
    /// A candidate an insertion restricted to some strips refused, and the strips it needs.
    struct Refused {
        Candidate candidate;
        StripRange needed;
    };
    /// The working state of one task of a level (a strip or a pair of strips). Cache-line
    /// aligned: the workers run neighbouring tasks at once.
    struct alignas(64) TaskState {
        RefineMesh::InsertScratch insert;
        std::vector<Refused> refused;
        std::size_t inserted = 0;
        std::size_t triangles = 0;
        /// Candidates refused in the last drain.
        std::size_t deferred = 0;
    };
    /// A strip: its candidates and its task's state.
    struct Strip {
        /// Candidates of the triangles within the strip, and of those spanning it and the next.
        CandidateQueue queue;
        CandidateQueue pairQueue;
        TaskState task;
        /// The strip's vertex ids (one reserved per valid cell of the strip): the first and the
        /// next free one; and its region of mesh slots.
        VertexId firstVertex = 0;
        VertexId nextVertex = 0;
        unsigned region = 0;
    };

    /// Cuts the columns into strips and reserves their vertex ids and slots.
    void planStrips();
    void startFromHull();
    void insertSeedCells();
    /// Candidates of the first triangles, scanned on the workers: they cover every valid cell.
    void scanFirstTriangles();
    /// Where `cell` lies in the TIN.
    [[nodiscard]] Point2 position(std::uint32_t cell) const {
        return m_positions.empty() ? m_grid->cellCentre(cell) : m_positions[cell];
    }
    [[nodiscard]] std::uint8_t stripOfCell(std::uint32_t cell) const {
        return m_columnStrip[cell % static_cast<std::uint32_t>(m_grid->width)];
    }
    /// Levels until no candidate is above the target or a limit is reached.
    void runLevels(const ProgressCallback& progress);
    /// The parallel steps of a level: every strip, and every pair of neighbouring strips,
    /// on the workers, as planLevel orders them (level_tasks.hpp). Each task inserts its
    /// queue's candidates above `level`, at most `quota`, restricted to its strips; a pair
    /// also takes the candidates its strips refused for needing both.
    void runStripsAndPairs(double level, std::size_t quota, const ProgressCallback& progress);
    /// Moves the candidates strips k and k + 1 refused for needing both to their pair's queue.
    void takeRefusedByStrips(std::uint8_t k);
    /// Inserts `queue`'s candidates above `level` restricted to `allowed`, at most `quota`,
    /// with `task`'s working state; found candidates are routed, refused ones kept in
    /// task.refused.
    void drain(CandidateQueue& queue, StripRange allowed, double level, std::size_t quota,
               TaskState& task);
    /// After a level's tasks: the candidates they refused for needing three strips or more
    /// go to the shared queue.
    void queueRefusedInShared();
    /// The shared candidates above `level`, by one thread, in priority order, unrestricted.
    /// With `exactLimits`, stops exactly at a limit (and returns false); candidates then go
    /// to the shared queue only, so this is plain greedy insertion.
    bool runShared(double level, bool exactLimits, const ProgressCallback& progress);
    /// runShared without limits, in batches (docs/algorithms.md): every candidate above
    /// `level` whose triangle is still there is inserted, the highest first, and then every
    /// triangle made is scanned once; until no candidate is above `level`.
    void runSharedInBatches(double level, const ProgressCallback& progress);
    /// Moves every strip's candidates to the shared queue (for the exact finish).
    void gatherIntoShared();
    /// Inserts `candidate`'s cell restricted to `allowed`, with the vertex ids and slots of the
    /// cell's strip. Returns the triangles added, 0 when refused (see RefineMesh::tryInsert).
    int insert(const Candidate& candidate, StripRange allowed, RefineMesh::InsertScratch& scratch,
               int maxAdded);
    /// Makes `vertex` the vertex of `cell`.
    void setVertex(VertexId vertex, std::uint32_t cell);
    /// The highest priority queued anywhere, -inf when nothing is.
    [[nodiscard]] double highestPriority();
    /// Points that may still be inserted under the limits (SIZE_MAX without one).
    [[nodiscard]] std::size_t budget() const;
    [[nodiscard]] std::size_t pointCount() const;
    /// Whether `candidate` still stands: its triangle unchanged and its cell no vertex.
    [[nodiscard]] bool isLive(const Candidate& candidate) const;
    /// isLive for CandidateQueue::top, which requests the memory it reads ahead.
    struct LiveTest {
        const GreedyRefiner* refiner;
        bool operator()(const Candidate& candidate) const { return refiner->isLive(candidate); }
        void request(const Candidate& candidate) const {
            __builtin_prefetch(&refiner->m_mesh->triangle(candidate.triangle));
            __builtin_prefetch(&refiner->m_flags[candidate.cell]);
        }
    };
    /// With positions, the levels' pixel-space scans only approximate the TIN's triangles
    /// (the map from pixels to positions bends straight lines, and shifts errors by up to a
    /// millimetre on a 90 m grid). This queues what the exact check of located_check.hpp
    /// still finds and runs the levels again, pass after pass, until the check finds nothing
    /// or a limit is reached. Each pass checks the whole TIN, so the result stays the same
    /// for any thread count.
    void completeAtPositions(const ProgressCallback& progress);
    /// Queues a candidate by the strips its triangle spans: the strip's queue, the pair's, or
    /// the shared queue. Touches only queues of those strips: safe from a task restricted to
    /// strips that include them.
    void route(const Candidate& candidate);
    [[nodiscard]] PixelCorner corner(VertexId v) const;
    /// Prepares the scan of a triangle (see TriangleScan); false when it has nothing to
    /// measure.
    bool prepareScan(TriId node, TriangleScan& scan) const;
    /// The candidate of a triangle from its scan, if it has one worth inserting.
    [[nodiscard]] std::optional<Candidate> candidateOf(TriId node, const ScanResult& result) const;
    /// Scans triangles, whose memory requests overlap (kMaxFan at a time), and passes each
    /// candidate found to `found`.
    template <class Found> void scanAll(std::span<const TriId> nodes, Found&& found) const;
    /// scanAll on the workers, for triangles too large for one thread (early on, when they
    /// span much of the raster): their rows are measured in bands. The same candidates as
    /// scanAll.
    template <class Found> void scanOnWorkers(std::span<const TriId> nodes, Found&& found);
    /// Scans an insertion's fan made by one thread alone (the shared step), on the workers
    /// when it covers many cells.
    template <class Found> void scanFan(std::span<const TriId> nodes, Found&& found);
    [[nodiscard]] double progressFraction(double topPriority) const;
    /// progressFraction, never below what was reported before: a level reports its target's
    /// fraction, and the shared step after it the (higher) priorities it inserts.
    [[nodiscard]] double nextProgressFraction(double topPriority);
    /// Calls `progress` (from the calling thread only); throws Cancelled when it says stop.
    void report(const ProgressCallback& progress, double topPriority);

    /// The caller's: grid, positions, flags and workers outlive the refiner (never null).
    const HeightGrid* m_grid;
    std::span<const Point2> m_positions;
    std::span<std::uint8_t> m_flags;
    GridView m_view;
    RefineOptions m_options;
    RoundWorkers* m_workers;
    /// Candidates at or below this are not inserted: maxError, or -1 to use every cell.
    double m_threshold = -1.0;
    /// Strip of each column; the strips.
    std::vector<std::uint8_t> m_columnStrip;
    std::vector<std::uint32_t> m_seedCells;
    std::vector<Strip> m_strips;
    /// The state of the task of each pair of strips (k, k + 1).
    std::vector<TaskState> m_pairTasks;
    /// By vertex id: the hull's first, then each strip's range.
    HugePageBuffer<RefineVertex> m_vertices;
    std::optional<RefineMesh> m_mesh;
    /// Candidates of triangles spanning more than two strips, and the ones refused by pairs.
    CandidateQueue m_shared;
    RefineMesh::InsertScratch m_sharedInsert;
    std::size_t m_triangles = 0;
    std::size_t m_hullPoints = 0;
    std::size_t m_levels = 0;
    std::size_t m_deferred = 0;
    std::size_t m_pairInsertions = 0;
    std::size_t m_sharedInsertions = 0;
    std::size_t m_completionPasses = 0;
    double m_firstPriority = 0.0;
    double m_reportedFraction = 0.0;
    /// Set by the calling thread when progress asks to stop; the workers then stop early.
    std::atomic<bool> m_cancelled{false};
    RefineStop m_stop = RefineStop::ErrorReached;
};

/// The refiner's counts into `figures`, a RefineResult or a tile's TileRefinement (the same
/// field names).
template <class Figures> void copyRefinerCounts(const GreedyRefiner& refiner, Figures& figures) {
    figures.hullPoints = refiner.hullPoints();
    figures.strips = refiner.strips();
    figures.levels = refiner.levels();
    figures.deferredCandidates = refiner.deferred();
    figures.pairInsertions = refiner.pairInsertions();
    figures.sharedInsertions = refiner.sharedInsertions();
    figures.meshBytes = refiner.meshBytes();
}

/// RefineOptions::validate's check: throws terratin::Error naming `which` ("the TIN", "a
/// tile's TIN") and the first problem when `mesh` is not exactly Delaunay.
void checkExactlyDelaunay(const TinMesh& mesh, const std::string& which);

} // namespace terratin::detail

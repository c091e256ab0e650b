#pragma once
/// @file
/// The greedy insertion loop (Garland & Heckbert's "greedy insertion" with a priority queue of
/// per-triangle candidates), in rounds of several non-conflicting insertions.
///
/// A round pops up to `roundCandidates` live candidates in priority order and, for each,
/// finds the triangles its insertion can change: its Bowyer-Watson cavity (every triangle
/// whose circumcircle contains the cell, cocircular included, found by a search from the
/// triangle holding it; Lawson's flips never leave the cavity) plus the cavity's neighbours,
/// whose links are rewritten. A candidate whose set meets an earlier accepted one waits for a
/// later round. The accepted insertions touch disjoint triangles, so they commute: the
/// workers insert them in any order and the triangulation is the same as inserting them one
/// after the other, for any number of threads. Each worker then scans the new triangles
/// around its points (the cells inside, the farthest from the new plane) and the candidates
/// go back into the queue. A popped candidate is stale when its triangle's slot changed since
/// (RefineMesh versions) or its cell became a vertex (lazy invalidation).
///
/// Priorities: a triangle covering an open hole's cell and a valid non-vertex cell is
/// refined before any error (priority +inf), so the triangles finally dropped over holes hold
/// no valid cell that another triangle would not cover; otherwise the priority is the largest
/// error, and only errors above the target become candidates. Ties: the lowest cell index.

#include "candidate_queue.hpp"
#include "cell_flags.hpp"
#include "grid_scan.hpp"
#include "triangle_scan.hpp"
#include "round_workers.hpp"

#include "refine_mesh.hpp"

#include "terratin/progress.hpp"
#include "terratin/refine/refine.hpp"

#include <cstdint>
#include <cstdlib>
#include <memory>
#include <optional>
#include <span>
#include <vector>

namespace terratin::detail {

class GreedyRefiner {
public:
    /// `flags` from makeCellFlags; the refiner marks vertices in it. `positions`: where each
    /// cell lies in the TIN (refine's positions), or empty for the grid's cell centres.
    GreedyRefiner(const HeightGrid& grid, std::span<const Point2> positions, CellFlags& flags,
                  const RefineOptions& options, RoundWorkers& workers);

    /// Runs to the target or a limit. Throws Cancelled when `progress` returns false.
    void run(const ProgressCallback& progress);

    /// The Delaunay triangulation of the chosen cells as a TinMesh (vertices at the cells'
    /// positions, sourceIndex = cell index).
    [[nodiscard]] TinMesh extract() const;

    [[nodiscard]] RefineStop stop() const { return m_stop; }
    [[nodiscard]] std::size_t hullPoints() const { return m_hullPoints; }
    [[nodiscard]] std::size_t rounds() const { return m_rounds; }
    [[nodiscard]] std::size_t deferred() const { return m_deferred; }
    /// Passes of completeAtPositions (0 without positions).
    [[nodiscard]] std::size_t completionPasses() const { return m_completionPasses; }
    [[nodiscard]] std::size_t meshBytes() const { return m_mesh->memoryBytes(); }

private:
    struct Accepted {
        VertexId vertex;
        TriId leaf;
    };
    /// A vertex's cell in pixel coordinates and its elevation, for the scans.
    struct VertexPixel {
        std::int32_t col;
        std::int32_t row;
        float z;
    };

    void startFromHull();
    /// Where `cell` lies in the TIN.
    [[nodiscard]] Point2 position(std::uint32_t cell) const {
        return m_positions.empty() ? m_grid.cellCentre(cell) : m_positions[cell];
    }
    /// Insertion rounds until the queue is empty or a limit is reached.
    void runRounds(const ProgressCallback& progress);
    /// With positions, the rounds' pixel-space scans only approximate the TIN's triangles
    /// (the map from pixels to positions bends straight lines, and shifts errors by up to a
    /// millimetre on a 90 m grid). This queues what the exact check of located_check.hpp
    /// still finds and runs the rounds again, pass after pass, until the check finds nothing
    /// or a limit is reached. Each pass checks the whole TIN, so the result stays the same
    /// for any thread count.
    void completeAtPositions(const ProgressCallback& progress);
    [[nodiscard]] PixelCorner corner(VertexId v) const;
    /// Prepares the scan of a triangle (see TriangleScan); false when it has nothing to
    /// measure.
    bool prepareScan(TriId node, TriangleScan& scan) const;
    /// The candidate of a triangle from its scan, if it has one worth inserting.
    [[nodiscard]] std::optional<Candidate> candidateOf(TriId node, const ScanResult& result) const;
    /// Scans a triangle and appends its candidate, if any, to `found`.
    void scanInto(TriId node, std::vector<Candidate>& found) const;
    /// scanInto for several leaves, whose memory requests overlap (kMaxFan at a time).
    void scanAllInto(std::span<const TriId> nodes, std::vector<Candidate>& found) const;
    /// The triangles inserting a point can change: the one holding it, the cavity, the ring.
    /// Cache-line aligned: the workers fill neighbouring zones, and a zone's vector header
    /// changes with every push_back; sharing a line would bounce it between the cores.
    struct alignas(64) Zone {
        TriId leaf = kNoTriangle;
        /// Change in the number of output triangles: 2, or 1 on the hull.
        int growth = 2;
        std::vector<TriId> nodes;
    };
    /// Whether `candidate` still stands: its triangle unchanged and its cell no vertex.
    [[nodiscard]] bool isLive(const Candidate& candidate) const;
    /// Appends the next `count` live candidates in queue order (fewer if it runs out), and
    /// drops the stale ones met on the way. Rounds are made of live candidates only: counting
    /// stale ones would make a round's content depend on the order of equal candidates.
    void popLive(std::size_t count, std::vector<Candidate>& out);
    /// Like popLive, from `early` (candidates popped before, in queue order) merged with the
    /// queue; the early ones not taken go back into the queue and `early` is cleared.
    void mergeLive(std::size_t count, std::vector<Candidate>& early, std::vector<Candidate>& out);
    /// Fills `zone` for `vertex` (already in m_points), searching from the triangle `start`.
    /// Reads the mesh only: safe from several threads while nothing edits it.
    void findZone(VertexId vertex, TriId start, Zone& zone) const;
    /// Claims the zone's triangles for this round, unless an accepted insertion of the round
    /// claimed one of them (then nothing is claimed).
    bool claim(const Zone& zone, std::uint32_t stamp);
    /// Whether claim would succeed, without claiming.
    [[nodiscard]] bool claimFree(const Zone& zone, std::uint32_t stamp) const;
    /// A worker's legalisation stack and the candidates it found, on cache lines of their
    /// own (see Zone).
    struct alignas(64) WorkerScratch {
        RefineMesh::Scratch mesh;
        std::vector<TriId> fan;
        std::vector<Candidate> found;
    };
    /// Inserts one accepted point and appends the candidates of its new triangles to
    /// scratch.found.
    void insert(const Accepted& accepted, WorkerScratch& scratch);
    void addVertex(std::uint32_t cell);
    /// Whether `vertex` may lie inside or on the circumcircle of `node`: a floating-point test
    /// erring towards "yes" (a larger claim is still a correct one, and grids make exact
    /// cocircularity tests common).
    [[nodiscard]] bool mayBeInCircle(const MeshTriangle& node, VertexId vertex) const;
    [[nodiscard]] double progressFraction(double topPriority) const;

    const HeightGrid& m_grid;
    std::span<const Point2> m_positions;
    CellFlags& m_flags;
    GridView m_view;
    RefineOptions m_options;
    RoundWorkers& m_workers;
    /// Candidates at or below this are not inserted: maxError, or -1 to use every cell.
    double m_threshold = -1.0;
    std::size_t m_capacity = 0;
    HugePageBuffer<Point2> m_points;
    std::vector<std::uint32_t> m_vertexCell;
    std::vector<VertexPixel> m_vertexPixel;
    std::optional<RefineMesh> m_mesh;
    CandidateQueue m_queue;
    std::size_t m_triangles = 0;
    std::size_t m_hullPoints = 0;
    std::size_t m_rounds = 0;
    std::size_t m_deferred = 0;
    std::size_t m_completionPasses = 0;
    double m_firstPriority = 0.0;
    RefineStop m_stop = RefineStop::ErrorReached;
};

} // namespace terratin::detail

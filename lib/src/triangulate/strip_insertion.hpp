#pragma once
/// @file
/// The strip method: history-free parallel Delaunay insertion by spatial ownership. Each
/// thread inserts the points of its own vertical strip into the CavityMesh, touching only its
/// strip's triangles (cavity_mesh.hpp); points refused by a strip boundary are retried with
/// strips merged in pairs, level by level, and what is left goes to one thread.
/// docs/algorithms.md ("The strip method") describes the levels.
///
/// The result is exactly Delaunay (each insertion is an exact Bowyer-Watson step) and depends
/// only on the points, the order and the strip count: thread timing never changes it.

#include "cavity_mesh.hpp"

#include "terratin/geometry/point.hpp"
#include "terratin/progress.hpp"

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace terratin::detail {

class StripTriangulator {
public:
    /// A round starts at the first level whose groups get at least this many points each
    /// (level 0: one strip each): below, starting the threads and the deferred points cost
    /// more than they save. With no such level it runs on one thread.
    static constexpr std::size_t kMinimumPointsPerStrip = 4096;
    /// Refused points fewer than this go straight to the single thread rather than start
    /// the threads of another level.
    static constexpr std::size_t kMinimumRetriedPoints = 256;

    /// `points`: distinct, not all collinear; they must outlive insertAll. `strips`:
    /// threads of level 0 (1: a plain sequential Bowyer-Watson insertion).
    /// `minimumPointsPerStrip`: see kMinimumPointsPerStrip (tests lower it).
    StripTriangulator(std::span<const Point2> points, unsigned strips,
                      std::size_t minimumPointsPerStrip = kMinimumPointsPerStrip);

    /// Inserts every vertex of `order` (each point once), whose BRIO rounds begin at
    /// `roundStarts`. Calls `progress` from the calling thread between rounds, and every
    /// kWatchInterval while a level's threads run (watched_threads.hpp); throws Cancelled
    /// when it returns false.
    void insertAll(std::span<const std::uint32_t> order, std::span<const std::size_t> roundStarts,
                   const ProgressCallback& progress);

    /// The mesh (CavityMesh::extract): the points need not outlive insertAll for this.
    void extract(MeshArray<std::uint32_t>& triangles, MeshArray<std::int32_t>& neighbours,
                 unsigned threads) const {
        m_mesh.extract(triangles, neighbours, threads);
    }

    [[nodiscard]] unsigned strips() const { return m_strips; }
    /// Points left to the single-threaded insertion of the last level (small rounds excluded).
    [[nodiscard]] std::size_t deferredPoints() const { return m_deferred; }
    [[nodiscard]] std::size_t memoryBytes() const {
        return m_mesh.memoryBytes() + m_vertexStrip.size();
    }

private:
    /// Inserts `points` one by one, unrestricted, on the calling thread.
    void insertSequentially(std::span<const std::uint32_t> points);
    /// Groups of strips merged at `level` (strips s with the same s >> level).
    [[nodiscard]] unsigned groupsAt(unsigned level) const { return ((m_strips - 1) >> level) + 1; }
    /// The round's points from `level` on, level by level (docs/algorithms.md); `fraction` is
    /// what the watching thread reports to `progress` meanwhile.
    void insertRoundInGroups(std::span<const std::uint32_t> round, unsigned level,
                             const ProgressCallback& progress, double fraction);
    /// A level's points by group, each group keeping the given (Hilbert) order: group g's are
    /// points[start[g]] to points[start[g + 1] - 1].
    struct LevelPoints {
        std::vector<std::size_t> start;
        HugePageArray<std::uint32_t> points;
        [[nodiscard]] std::size_t size(unsigned group) const {
            return start[group + 1] - start[group];
        }
    };
    [[nodiscard]] LevelPoints groupPoints(std::span<const std::uint32_t> points,
                                          unsigned level) const;
    /// For every kCheckpointStride-th point of each group, the triangle holding it now if the
    /// group may touch it, else kNoCavityTriangle (insertAtLevel says why); on the groups'
    /// threads.
    std::vector<std::vector<CavityTriangleId>> findCheckpoints(const LevelPoints& grouped,
                                                               unsigned level,
                                                               const ProgressCallback& progress,
                                                               double fraction);
    /// One level: each group's points on a thread of its own. Returns the points refused.
    std::vector<std::vector<std::uint32_t>> insertAtLevel(std::span<const std::uint32_t> points,
                                                          unsigned level,
                                                          const ProgressCallback& progress,
                                                          double fraction);
    /// body(group) for each of `groups` on a thread of its own, watched by the calling thread
    /// (watched_threads.hpp), which reports `fraction`; throws Cancelled once every thread
    /// has seen m_stop and returned, when the callback asked to stop.
    template <class Body>
    void runGroups(unsigned groups, const ProgressCallback& progress, double fraction, Body&& body);
    [[nodiscard]] bool stopping() const { return m_stop.load(std::memory_order_relaxed); }
    /// The level at which a point refused at `level` may succeed: the first at which the
    /// boundary of its group nearer to it lies inside a group.
    [[nodiscard]] unsigned retryLevel(std::uint32_t point, unsigned level) const;

    unsigned m_strips;
    std::size_t m_minimumPointsPerStrip;
    std::span<const Point2> m_points;
    /// Strip s holds the points with m_thresholds[s - 1] <= x < m_thresholds[s].
    std::vector<double> m_thresholds;
    /// The strip of each vertex (empty with one strip).
    HugePageArray<std::uint8_t> m_vertexStrip;
    /// The first level with a single group: its points are inserted unrestricted.
    unsigned m_topLevel = 0;
    CavityMesh m_mesh;
    /// One per strip (its points, at any level), and last the one of the unrestricted
    /// insertions.
    std::vector<CavityMesh::Scratch> m_scratch;
    CavityTriangleId m_hint = 0;
    std::size_t m_deferred = 0;
    /// Set by the watching thread when the progress callback asks to stop; every group's
    /// loop tests it once per point.
    std::atomic<bool> m_stop{false};
};

} // namespace terratin::detail

#pragma once
/// @file
/// The strip method: history-free parallel Delaunay insertion by spatial ownership.
///
/// The paper's methods share one triangulation between all threads and pay for it with a
/// shared queue (batch) or with circumcircle tests against every other thread's point
/// (circum-circle). Here the plane is cut into vertical strips of equal point counts, one per
/// thread, and each BRIO round runs in two phases:
/// 1. Every thread inserts its strip's points of the round into the CavityMesh, touching
///    only triangles whose corners all lie in its strip (cavity_mesh.hpp explains why
///    threads then never meet). A point whose walk or cavity reaches a triangle that spans
///    two strips is deferred; no lock, no atomic but the slot counter, no waiting.
/// 2. One thread inserts the deferred points, unrestricted.
/// Only points within about one triangle of a strip boundary are deferred (a fraction of a
/// percent of a million uniform points), so phase 1 does almost all the work.
///
/// The result is exactly Delaunay (each insertion is an exact Bowyer-Watson step) and depends
/// only on the points, the order and the strip count: thread timing never changes it.

#include "cavity_mesh.hpp"

#include "terratin/geometry/point.hpp"
#include "terratin/progress.hpp"

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace terratin::detail {

class StripTriangulator {
public:
    /// A round runs in strips only when every strip gets at least this many points: below,
    /// starting the threads and the deferred points cost more than they save.
    static constexpr std::size_t kMinimumPointsPerStrip = 4096;

    /// `points`: distinct, not all collinear; they must outlive the triangulator. `strips`:
    /// threads of phase 1 (1: a plain sequential Bowyer-Watson insertion).
    /// `minimumPointsPerStrip`: see kMinimumPointsPerStrip (tests lower it).
    StripTriangulator(std::span<const Point2> points, unsigned strips,
                      std::size_t minimumPointsPerStrip = kMinimumPointsPerStrip);

    /// Inserts every vertex of `order` (each point once), whose BRIO rounds begin at
    /// `roundStarts`. Calls `progress` between rounds; throws Cancelled when it returns false.
    void insertAll(std::span<const std::uint32_t> order, std::span<const std::size_t> roundStarts,
                   const ProgressCallback& progress);

    void extract(MeshArray<std::uint32_t>& triangles, MeshArray<std::int32_t>& neighbours,
                 unsigned threads) const {
        m_mesh.extract(triangles, neighbours, threads);
    }

    [[nodiscard]] unsigned strips() const { return m_strips; }
    /// Points phase 1 left to phase 2.
    [[nodiscard]] std::size_t deferredPoints() const { return m_deferred; }
    [[nodiscard]] std::size_t memoryBytes() const {
        return m_mesh.memoryBytes() + m_vertexStrip.size();
    }

private:
    /// Inserts `points` one by one, unrestricted, on the calling thread.
    void insertSequentially(std::span<const std::uint32_t> points);
    /// Phases 1 and 2 for one round.
    void insertRoundInStrips(std::span<const std::uint32_t> round);

    unsigned m_strips;
    std::size_t m_minimumPointsPerStrip;
    std::span<const Point2> m_points;
    /// The strip of each vertex (empty with one strip).
    std::vector<std::uint8_t> m_vertexStrip;
    CavityMesh m_mesh;
    /// One per strip (phase 1), and last the one of the single-threaded insertions.
    std::vector<CavityMesh::Scratch> m_scratch;
    CavityTriangleId m_hint = 0;
    std::size_t m_deferred = 0;
};

} // namespace terratin::detail

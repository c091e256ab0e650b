#pragma once
/// @file
/// The state of one circum-circle worker: what it publishes to the others (WorkerSlot) and
/// what it keeps to itself (Worker). The protocol they serve is described in
/// docs/algorithms.md ("The circum-circle method").

#include "box.hpp"
#include "circumcircle_insertion.hpp"
#include "owner_tag.hpp"

#include <atomic>
#include <cstdint>
#include <optional>
#include <vector>

namespace terratin::detail {

/// WorkerSlot::activePoint of a worker that shows no point.
inline constexpr VertexId kNoVertex = 0xFFFFFFFFU;

/// The bounding box of the points a worker inserts in its share of the current round. It
/// changes once per round, so the others read it from their caches; the active point beside
/// it changes twice per insertion and costs a cache miss to read.
struct alignas(64) WorkerRegion {
    std::atomic<double> minX{0.0};
    std::atomic<double> minY{0.0};
    std::atomic<double> maxX{-1.0}; // empty until the worker's first round
    std::atomic<double> maxY{-1.0};

    void store(const Box& box) {
        minX.store(box.minX, std::memory_order_relaxed);
        minY.store(box.minY, std::memory_order_relaxed);
        maxX.store(box.maxX, std::memory_order_relaxed);
        maxY.store(box.maxY, std::memory_order_relaxed);
    }

    [[nodiscard]] Box load() const {
        return {minX.load(std::memory_order_relaxed), minY.load(std::memory_order_relaxed),
                maxX.load(std::memory_order_relaxed), maxY.load(std::memory_order_relaxed)};
    }
};

/// What a worker publishes to the others. One slot each, the region on a cache line of its
/// own: the active point is polled constantly.
struct alignas(64) WorkerSlot {
    /// The point being inserted, or kNoVertex: the paper's pool of tested points.
    std::atomic<VertexId> activePoint{kNoVertex};
    /// Set by another worker that resolved a deadlock against this one.
    std::atomic<bool> overridden{false};
    /// The worker this one waits for, if any. Guarded by TriangleClaims' wait mutex.
    std::optional<WorkerIndex> waitingFor;
    /// The worker's current owner tag, read by a worker that overrides it.
    std::atomic<OwnerTag> tag{};
    /// No node the worker creates for its current point, or any later one, has a lower id
    /// (see repair_rendezvous.hpp).
    std::atomic<NodeId> lowestNewNode{0};
    /// Points the worker has inserted: a worker that stepped aside waits for it to change.
    std::atomic<std::uint32_t> finishedPoints{0};
    /// Where activePoint lies during the worker's current round.
    WorkerRegion region;
};

/// Why a worker gave up an unchanged attempt to break a deadlock: the worker it would have
/// waited for, and that worker's count of finished points then. The worker withdraws its
/// point until the count changes (TriangleClaims::stepAside).
struct BackOff {
    WorkerIndex blocker = 0;
    std::uint32_t blockerFinishedPoints = 0;
};

/// A worker's private state.
struct Worker {
    WorkerIndex index = 0;
    /// Owner tag written into the triangles it holds; a new one for every attempt.
    OwnerTag tag;
    std::vector<NodeId> held;
    PendingEdges pending;
    /// Points inserted so far (published in WorkerSlot::finishedPoints).
    std::uint32_t finishedPoints = 0;
    /// A triangle this worker created for its previous point: where walks start.
    NodeId recent = 0;
    /// Set when the worker learns it was overridden: an overriding worker may have taken
    /// some of the triangles it holds.
    bool overridden = false;
    /// Set once the current attempt has subdivided: from then on it cannot simply restart.
    bool changedMesh = false;
    /// Set when the worker gave up its last attempt to break a deadlock.
    std::optional<BackOff> backOff;
    CircumcircleStatistics statistics;
};

} // namespace terratin::detail

#pragma once
/// @file
/// Where the circum-circle method's workers stop together to repair the triangulation after
/// an override (circumcircle_insertion.hpp).
///
/// Why a repair of the newest leaves suffices: let the first override since the last repair
/// (or the start) take a triangle at time T. Every insertion that completed before T ran as
/// one atomic step on triangles it held (two-phase locking on the owner tags), and no
/// unfinished one that had changed anything released a triangle before T (an attempt given
/// up before its subdivision changed nothing, so it does not count), so those insertions
/// serialise before all others and leave an exactly Delaunay triangulation. An edge whose two
/// leaves both come from them is therefore legal; every other leaf was created by an
/// insertion still running at T or begun later. Each worker publishes, as it starts a point,
/// the lowest node id it can create from then on; the smallest of these read at T bounds all
/// such leaves from below, and DagTriangulator::repairEdgesFrom that id makes the
/// triangulation Delaunay again. The workers meet first, between two of their points, so that
/// no one holds a triangle while the repair flips.

#include "dag_triangulator.hpp"

#include <atomic>
#include <condition_variable>
#include <cstddef>
#include <mutex>

namespace terratin::detail {

class RepairRendezvous {
public:
    RepairRendezvous(DagTriangulator& triangulator, unsigned workers)
        : m_triangulator(triangulator), m_workingWorkers(workers) {}

    /// Asks for a repair of the leaves from `firstNode` on; several requests before the
    /// repair combine into the lowest.
    void request(NodeId firstNode);

    /// True while a repair is asked for: a worker then calls arrive() before its next point.
    [[nodiscard]] bool requested() const { return m_requested.load(std::memory_order_acquire); }

    /// Called by a worker between two points, holding no triangle: waits until every worker
    /// still working has arrived or left; the last one to come runs the repair. Returns at
    /// once when no repair is asked for, or after stop().
    void arrive();

    /// Called by a worker that has inserted all its points (or is stopping): the others no
    /// longer wait for it, and it runs the repair if it was the last they waited for.
    void leave();

    /// Wakes every waiting worker without a repair: the run is failing or cancelled.
    void stop();

    /// Repairs run and the flips they made.
    [[nodiscard]] std::size_t repairs() const { return m_repairs; }
    [[nodiscard]] std::size_t flips() const { return m_flips; }

private:
    /// With m_mutex held: runs the repair when every working worker is here.
    void repairIfAllArrived();

    DagTriangulator& m_triangulator;
    std::mutex m_mutex;
    std::condition_variable m_repaired;
    std::atomic<bool> m_requested{false};
    /// Guarded by m_mutex, as everything below.
    NodeId m_firstNode = kNoNode;
    unsigned m_workingWorkers;
    unsigned m_arrivedWorkers = 0;
    /// Repairs done: a waiting worker knows its repair is over when this changes.
    std::size_t m_repairs = 0;
    bool m_stopped = false;
    std::size_t m_flips = 0;
};

} // namespace terratin::detail

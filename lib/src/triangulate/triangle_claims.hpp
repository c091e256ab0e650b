#pragma once
/// @file
/// How circum-circle workers take triangles from one another: the owner-tag compare-and-swap,
/// the test of the others' points against a triangle's circumcircle, the waits, and the
/// deadlock resolution by stepping aside or overriding. docs/algorithms.md ("The circum-circle
/// method") tells the whole protocol and why it is exact; the comments here say why each step
/// is done the way it is.

#include "circumcircle_worker.hpp"
#include "conflict_region.hpp"
#include "dag_triangulator.hpp"
#include "owner_tag.hpp"
#include "repair_rendezvous.hpp"

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <mutex>
#include <optional>
#include <span>
#include <thread>
#include <utility>
#include <vector>

namespace terratin::detail {

/// Workers from which the conflict test filters by region (workerInCircle). With fewer, the
/// circumcircle computed on every take cost more than the cache misses it saved (figures in
/// docs/benchmarks.md).
inline constexpr unsigned kRegionFilterWorkers = 4;

/// The workers' published slots and the protocol by which each takes the triangles it
/// changes. A worker takes (take) every triangle it reads the neighbours of or changes, holds
/// them until its point is in, and then releases them all (releaseAll).
class TriangleClaims {
public:
    /// `repair` is asked for a repair before every override; both it and `triangulator` must
    /// outlive this object.
    TriangleClaims(DagTriangulator& triangulator, unsigned workers, RepairRendezvous& repair)
        : m_triangulator(&triangulator), m_slots(workers), m_repair(&repair) {}

    /// The private state of worker `index`, its first tag published.
    [[nodiscard]] Worker startWorker(WorkerIndex index) {
        Worker worker;
        worker.index = index;
        worker.tag = OwnerTag::firstOf(index);
        m_slots[index].tag.store(worker.tag, std::memory_order_relaxed);
        return worker;
    }

    [[nodiscard]] unsigned workers() const { return static_cast<unsigned>(m_slots.size()); }

    [[nodiscard]] bool filterByRegion() const { return m_slots.size() >= kRegionFilterWorkers; }

    /// Publishes the box of the points the worker inserts next. A reader may pair a stale box
    /// with a new active point around a round's start and skip a real conflict; the owner
    /// tags still keep every triangle to one worker, so that costs at most an override.
    void publishRegion(WorkerIndex index, std::span<const VertexId> points) {
        Box box;
        const SymbolicPredicates& predicates = m_triangulator->predicates();
        for (const VertexId v : points)
            box.add(predicates.point(v));
        m_slots[index].region.store(box);
    }

    /// Shows q to the others as the worker's point. The published point is a hint for the
    /// others' geometric test, not the guarantee (the owner tags are), so release stores
    /// suffice, not sequentially consistent ones.
    void showPoint(const Worker& worker, VertexId q) {
        WorkerSlot& self = m_slots[worker.index];
        self.lowestNewNode.store(m_triangulator->lowestFutureNodeOfThisThread(),
                                 std::memory_order_relaxed);
        self.activePoint.store(q, std::memory_order_release);
    }

    /// Withdraws the worker's point as soon as it is in: a point left published makes the
    /// others wait for nothing (measured: a wait on every other insertion).
    void withdrawPoint(const Worker& worker) {
        m_slots[worker.index].activePoint.store(kNoVertex, std::memory_order_release);
    }

    /// Publishes the worker's count of inserted points, which a worker that stepped aside
    /// for it waits on.
    void publishFinishedPoints(const Worker& worker) {
        // Only this worker writes its count: a plain store, not a locked increment.
        m_slots[worker.index].finishedPoints.store(worker.finishedPoints,
                                                   std::memory_order_release);
    }

    /// Takes triangle t for the worker. False when the worker was overridden meanwhile (it
    /// must give up what it holds), when it backed off (worker.backOff is set: it must give up
    /// what it holds and stepAside) or when the run is stopping.
    bool take(Worker& worker, NodeId t) {
        DagNode& node = m_triangulator->node(t);
        for (;;) {
            if (stopping())
                return false;
            std::uint32_t owner = node.owner.load(std::memory_order_acquire);
            if (owner == worker.tag.word())
                return true;
            std::optional<WorkerIndex> blocker = OwnerTag::holderOf(owner);
            if (!blocker) {
                blocker = workerInCircle(worker, node);
                if (!blocker) {
                    if (node.owner.compare_exchange_strong(owner, worker.tag.word(),
                                                           std::memory_order_acq_rel)) {
                        worker.held.push_back(t);
                        return true;
                    }
                    continue;
                }
            }
            const WaitResult wait = waitFor(worker, *blocker, t);
            switch (wait.outcome) {
            case WaitOutcome::Retry:
                continue;
            case WaitOutcome::Aborted:
                worker.overridden = true;
                return false;
            case WaitOutcome::BackOff:
                return false;
            case WaitOutcome::Override:
                // Ignore the circum-circle test; take the triangle even from the blocker's
                // overridden attempt: it is waiting and will give up when it sees its flag.
                owner = node.owner.load(std::memory_order_acquire);
                if ((owner == OwnerTag::kFreeWord || owner == wait.overriddenTag.word()) &&
                    node.owner.compare_exchange_strong(owner, worker.tag.word(),
                                                       std::memory_order_acq_rel)) {
                    worker.held.push_back(t);
                    return true;
                }
                continue;
            }
        }
    }

    /// Frees every triangle the worker holds and starts its next attempt, under a new tag.
    void releaseAll(Worker& worker) {
        if (std::exchange(worker.overridden, false)) {
            for (const NodeId n : worker.held) {
                // A triangle taken over by an overriding worker is no longer ours to free.
                std::uint32_t expected = worker.tag.word();
                m_triangulator->node(n).owner.compare_exchange_strong(expected, OwnerTag::kFreeWord,
                                                                      std::memory_order_release,
                                                                      std::memory_order_relaxed);
            }
        } else {
            // Only a worker that was overridden loses triangles (an override is decided
            // while its victim waits, and the victim always sees its flag when the wait
            // ends), so here every triangle is still ours: plain release stores, not a
            // locked read-modify-write each, which would drain the store buffer every time.
            for (const NodeId n : worker.held)
                m_triangulator->node(n).owner.store(OwnerTag::kFreeWord, std::memory_order_release);
        }
        worker.held.clear();
        worker.changedMesh = false;
        worker.tag = worker.tag.nextAttempt();
        m_slots[worker.index].tag.store(worker.tag, std::memory_order_relaxed);
    }

    /// After backing off (worker.backOff set), holding nothing: withdraws the point until the
    /// worker it would have waited for has finished its own. Published again at once, the
    /// point would keep that worker waiting (it is inside the circles around it), and the
    /// deadlock would recur for every triangle that worker still needs (measured: millions of
    /// deadlocks in a run on points of one circle).
    ///
    /// These waits cannot close a cycle: a worker steps aside only for one that is waiting
    /// (the deadlock was found along the chain of waits), hence not stepping aside itself,
    /// and a worker that stepped aside is waited for by no one: it holds nothing and shows
    /// no point. So the last of any cycle's waits would have begun for a worker that was
    /// already stepping aside.
    void stepAside(Worker& worker, VertexId q) {
        WorkerSlot& self = m_slots[worker.index];
        self.activePoint.store(kNoVertex, std::memory_order_release);
        const BackOff backOff = *worker.backOff;
        const WorkerSlot& blocker = m_slots[backOff.blocker];
        while (blocker.finishedPoints.load(std::memory_order_acquire) ==
                   backOff.blockerFinishedPoints &&
               !stopping())
            std::this_thread::yield();
        worker.backOff.reset();
        self.activePoint.store(q, std::memory_order_release);
    }

    [[nodiscard]] bool stopping() const { return m_stop.load(std::memory_order_acquire); }

    /// Makes every take and wait return false soon.
    void requestStop() { m_stop.store(true, std::memory_order_release); }

private:
    enum class WaitOutcome {
        /// The blocker let go of the triangle (or its point): try to take it again.
        Retry,
        /// Another worker overrode this one during the wait.
        Aborted,
        /// A deadlock, broken by giving up this worker's unchanged attempt (worker.backOff).
        BackOff,
        /// A deadlock, broken by overriding the blocker.
        Override,
    };

    /// How a wait for another worker ended.
    struct WaitResult {
        WaitOutcome outcome;
        /// With Override: the tag of the blocker's attempt overridden, whose triangles the
        /// worker may now take.
        OwnerTag overriddenTag;
    };

    /// Another worker whose point lies strictly inside the circumcircle of `node`, if any.
    /// Points too close to the circle for the floating-point filter count as outside: on
    /// near-cocircular data (an arc) the exact test went adaptive on nearly every call and
    /// took much of the run (docs/benchmarks.md), and the owner tags protect the triangles
    /// either way.
    /// From kRegionFilterWorkers on, workers whose region the circumcircle misses are skipped
    /// without reading their active point, which another core keeps rewriting. Reading all of
    /// them on every take, the method ran slower on 16 threads than on 1 (docs/benchmarks.md).
    [[nodiscard]] std::optional<WorkerIndex> workerInCircle(const Worker& worker,
                                                            const DagNode& node) const {
        const SymbolicPredicates& predicates = m_triangulator->predicates();
        const bool finite = predicates.isFinite(node.v[0]) && predicates.isFinite(node.v[1]) &&
                            predicates.isFinite(node.v[2]);
        const bool filter = filterByRegion() && finite;
        const Circle circle =
            filter ? Circle::through(predicates.point(node.v[0]), predicates.point(node.v[1]),
                                     predicates.point(node.v[2]))
                   : Circle{};
        for (WorkerIndex k = 0; k < m_slots.size(); ++k) {
            if (k == worker.index || (filter && !circle.mayReach(m_slots[k].region.load())))
                continue;
            const VertexId point = m_slots[k].activePoint.load(std::memory_order_acquire);
            if (point != kNoVertex &&
                predicates.surelyInside(node.v[0], node.v[1], node.v[2], point))
                return k;
        }
        return std::nullopt;
    }

    /// Waits while `blocker` keeps t, by holding it or by showing a point inside its
    /// circumcircle; first resolves the deadlock if waiting would close a cycle of waits.
    WaitResult waitFor(Worker& worker, WorkerIndex blocker, NodeId t) {
        WorkerSlot& self = m_slots[worker.index];
        {
            const std::lock_guard lock(m_waitMutex);
            if (waitsLeadTo(blocker, worker.index))
                return resolveDeadlock(worker, blocker);
            self.waitingFor = blocker;
        }
        ++worker.statistics.waits;
        const DagNode& node = m_triangulator->node(t);
        const VertexId watched = m_slots[blocker].activePoint.load(std::memory_order_acquire);
        while (stillBlocked(node, blocker, watched) &&
               !self.overridden.load(std::memory_order_acquire) && !stopping())
            std::this_thread::yield();
        const std::lock_guard lock(m_waitMutex);
        self.waitingFor.reset();
        const bool overridden = self.overridden.exchange(false, std::memory_order_acq_rel);
        return {overridden ? WaitOutcome::Aborted : WaitOutcome::Retry, {}};
    }

    /// With m_waitMutex held: whether the chain of waits from `from` reaches `self`. At most
    /// one step per worker: the chain may run into a cycle that `self` is not part of.
    [[nodiscard]] bool waitsLeadTo(WorkerIndex from, WorkerIndex self) const {
        std::optional<WorkerIndex> next = from;
        for (std::size_t steps = 0; next && *next != self && steps <= m_slots.size(); ++steps)
            next = m_slots[*next].waitingFor;
        return next == self;
    }

    /// With m_waitMutex held, when waiting for `blocker` would close a cycle of waits: a
    /// worker that has changed nothing yet breaks it by giving up its own attempt (no edge is
    /// left unchecked, and no repair is needed); otherwise it overrides the blocker.
    WaitResult resolveDeadlock(Worker& worker, WorkerIndex blocker) {
        if (!worker.changedMesh) {
            ++worker.statistics.backOffs;
            // The blocker is waiting: its count cannot change before the wait ends.
            worker.backOff =
                BackOff{blocker, m_slots[blocker].finishedPoints.load(std::memory_order_relaxed)};
            return {WaitOutcome::BackOff, {}};
        }
        // The blocker is waiting, so its attempt (and tag) cannot change until it sees the
        // flag and gives up.
        const OwnerTag overriddenTag = m_slots[blocker].tag.load(std::memory_order_relaxed);
        requestRepair();
        m_slots[blocker].overridden.store(true, std::memory_order_release);
        ++worker.statistics.overrides;
        return {WaitOutcome::Override, overriddenTag};
    }

    /// Whether `blocker` still holds the triangle of `node`, or still shows the point it
    /// showed when the wait began and that point is inside the triangle's circumcircle.
    [[nodiscard]] bool stillBlocked(const DagNode& node, WorkerIndex blocker,
                                    VertexId watchedPoint) const {
        if (OwnerTag::holderOf(node.owner.load(std::memory_order_acquire)) == blocker)
            return true;
        return watchedPoint != kNoVertex &&
               m_slots[blocker].activePoint.load(std::memory_order_acquire) == watchedPoint &&
               m_triangulator->predicates().surelyInside(node.v[0], node.v[1], node.v[2],
                                                         watchedPoint);
    }

    /// Called before an override takes its first triangle (repair_rendezvous.hpp).
    void requestRepair() {
        NodeId lowest = kNoNode;
        for (const WorkerSlot& slot : m_slots)
            lowest = std::min(lowest, slot.lowestNewNode.load(std::memory_order_relaxed));
        m_repair->request(lowest);
    }

    DagTriangulator* m_triangulator;
    std::vector<WorkerSlot> m_slots;
    RepairRendezvous* m_repair;
    std::atomic<bool> m_stop{false};
    /// Guards every WorkerSlot::waitingFor, and orders an override before its victim's
    /// look at its flag when its wait ends.
    std::mutex m_waitMutex;
};

} // namespace terratin::detail

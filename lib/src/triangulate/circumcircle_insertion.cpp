#include "circumcircle_insertion.hpp"

#include "conflict_region.hpp"
#include "repair_rendezvous.hpp"
#include "watched_threads.hpp"

#include "terratin/error.hpp"

#include <algorithm>
#include <array>
#include <atomic>
#include <exception>
#include <memory>
#include <mutex>
#include <thread>
#include <utility>
#include <vector>

namespace terratin::detail {

namespace {

constexpr VertexId kNoVertex = 0xFFFFFFFFU;

// A triangle's owner word: 0 when free, else the holder's index + 1 in the low bits and its
// attempt number above. Each attempt to insert a point takes triangles under a new tag, so
// an overriding worker, which may take its victim's triangles, takes only those of the
// attempt it overrode: never one the victim took again after giving up.
constexpr unsigned kWorkerBits = 12;
constexpr std::uint32_t kWorkerMask = (1U << kWorkerBits) - 1;
constexpr unsigned kMaxWorkers = kWorkerMask - 1;

std::uint32_t ownerTag(unsigned worker, std::uint32_t attempt) {
    return (attempt << kWorkerBits) | (worker + 1);
}

// The worker holding a triangle with this owner word, or -1 when it is free.
int holderOf(std::uint32_t owner) {
    return static_cast<int>(owner & kWorkerMask) - 1;
}

// Workers from which the conflict test filters by region (workerInCircle). With fewer, the
// circumcircle computed on every take cost more than the cache misses it saved (figures in
// docs/benchmarks.md).
constexpr unsigned kRegionFilterWorkers = 4;

// Workers add to the shared count of insertions (for the watching thread's progress
// reports) once per this many of their own.
constexpr std::size_t kCountBatch = 4096;

// The bounding box of the points a worker inserts in its share of the current round. It
// changes once per round, so the others read it from their caches; the active point beside
// it changes twice per insertion and costs a cache miss to read.
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

// What a worker publishes to the others. One slot each, the region on a cache line of its
// own: the active point is polled constantly.
struct alignas(64) WorkerSlot {
    /// The point being inserted, or kNoVertex: the paper's pool of tested points.
    std::atomic<VertexId> activePoint{kNoVertex};
    /// Set by another worker that resolved a deadlock against this one.
    std::atomic<bool> overridden{false};
    /// Worker this one waits for, or -1. Guarded by CircumcircleRun::m_waitMutex.
    int waitingFor = -1;
    /// The worker's current owner tag (ownerTag), read by a worker that overrides it.
    std::atomic<std::uint32_t> tag{0};
    /// No node the worker creates for its current point, or any later one, has a lower id
    /// (see repair_rendezvous.hpp).
    std::atomic<NodeId> lowestNewNode{0};
    /// Points the worker has inserted: a worker that stepped aside waits for it to change.
    std::atomic<std::uint32_t> finishedPoints{0};
    /// Where activePoint lies during the worker's current round.
    WorkerRegion region;
};

// A worker's private state.
struct Worker {
    unsigned index = 0;
    /// Owner tag written into the triangles it holds; a new one for every attempt.
    std::uint32_t tag = 0;
    std::uint32_t attempt = 0;
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
    /// When the worker gave up an unchanged attempt to break a deadlock (else -1): the worker
    /// it would have waited for, and that worker's count of finished points then (stepAside).
    int backedOffFrom = -1;
    std::uint32_t blockerFinishedPoints = 0;
    CircumcircleStatistics statistics;
};

// On a cache line of its own: it lives on the calling thread's stack, whose other writes
// would otherwise make every worker's read of the fields below a cache miss (a profile of
// `take` found it in the load of m_triangulator; docs/benchmarks.md).
class alignas(64) CircumcircleRun {
public:
    CircumcircleRun(DagTriangulator& triangulator, std::span<const VertexId> order,
                    std::span<const std::size_t> roundStarts, unsigned workers, bool walk)
        : m_triangulator(triangulator), m_order(order), m_roundStarts(roundStarts),
          m_slots(workers), m_walk(walk), m_repair(triangulator, workers) {}

    void work(unsigned index) {
        Worker worker;
        worker.index = index;
        worker.tag = ownerTag(index, 0);
        m_slots[index].tag.store(worker.tag, std::memory_order_relaxed);
        try {
            const std::size_t workers = m_slots.size();
            for (std::size_t round = 0; round < m_roundStarts.size() && !stopping(); ++round) {
                const std::size_t roundBegin = m_roundStarts[round];
                const std::size_t roundEnd =
                    round + 1 < m_roundStarts.size() ? m_roundStarts[round + 1] : m_order.size();
                const std::size_t length = roundEnd - roundBegin;
                const std::size_t begin = roundBegin + length * index / workers;
                const std::size_t end = roundBegin + length * (index + 1) / workers;
                if (filterByRegion())
                    publishRegion(index, m_order.subspan(begin, end - begin));
                for (std::size_t i = begin; i < end && !stopping(); ++i) {
                    if (m_repair.requested())
                        m_repair.arrive();
                    insertPoint(worker, m_order[i]);
                    const std::size_t sinceCounted = (i + 1 - begin) % kCountBatch;
                    if (sinceCounted == 0 || i + 1 == end)
                        m_inserted.fetch_add(sinceCounted == 0 ? kCountBatch : sinceCounted,
                                             std::memory_order_relaxed);
                }
            }
        } catch (...) {
            fail(std::current_exception());
        }
        releaseAll(worker);
        m_slots[index].activePoint.store(kNoVertex, std::memory_order_release);
        try {
            m_repair.leave(); // may run a repair, which allocates
        } catch (...) {
            fail(std::current_exception());
        }
        const std::lock_guard lock(m_statisticsMutex);
        m_statistics.waits += worker.statistics.waits;
        m_statistics.overrides += worker.statistics.overrides;
        m_statistics.backOffs += worker.statistics.backOffs;
        m_statistics.deferredEdges += worker.statistics.deferredEdges;
    }

    void finish() {
        if (m_failure)
            std::rethrow_exception(m_failure);
        if (m_cancelled.load())
            throw Cancelled("Triangulator: cancelled");
        m_statistics.repairs = m_repair.repairs();
        m_statistics.repairFlips = m_repair.flips();
    }

    [[nodiscard]] const CircumcircleStatistics& statistics() const { return m_statistics; }

    // The watching thread's report; false once the callback asked to stop.
    bool report(const ProgressCallback& progress) {
        const std::size_t done = m_inserted.load(std::memory_order_relaxed);
        if (!progress || progress(static_cast<double>(done) / static_cast<double>(m_order.size()),
                                  "triangulating"))
            return true;
        m_cancelled.store(true, std::memory_order_relaxed);
        return false;
    }

    void requestStop() {
        m_stop.store(true, std::memory_order_release);
        m_repair.stop();
    }

private:
    enum class WaitOutcome { Retry, Override, Aborted, BackOff };

    [[nodiscard]] bool filterByRegion() const { return m_slots.size() >= kRegionFilterWorkers; }

    // Publishes the box of the points the worker inserts next. A reader may pair a stale box
    // with a new active point around a round's start and skip a real conflict; the owner tags
    // still keep every triangle to one worker, so that costs at most an override.
    void publishRegion(unsigned index, std::span<const VertexId> points) {
        Box box;
        const SymbolicPredicates& predicates = m_triangulator.predicates();
        for (const VertexId v : points)
            box.add(predicates.point(v));
        m_slots[index].region.store(box);
    }

    bool stopping() const { return m_stop.load(std::memory_order_acquire); }

    void fail(std::exception_ptr failure) {
        {
            const std::lock_guard lock(m_failureMutex);
            if (!m_failure)
                m_failure = std::move(failure);
        }
        requestStop();
    }

    // The published point is a hint for the others' geometric test, not the guarantee (the
    // owner tags are), so release stores suffice, not sequentially consistent ones. It is
    // withdrawn as soon as the point is in: a point left published makes the others wait for
    // nothing (measured: a wait on every other insertion).
    void insertPoint(Worker& worker, VertexId q) {
        m_slots[worker.index].lowestNewNode.store(m_triangulator.lowestFutureNodeOfThisThread(),
                                                  std::memory_order_relaxed);
        m_slots[worker.index].activePoint.store(q, std::memory_order_release);
        NodeId hint = 0;
        while (!subdivide(worker, q, hint)) {
            releaseAll(worker);
            if (worker.backedOffFrom >= 0)
                stepAside(worker, q);
            if (stopping())
                return;
        }
        worker.changedMesh = true;
        legalize(worker, q);
        releaseAll(worker);
        WorkerSlot& self = m_slots[worker.index];
        self.activePoint.store(kNoVertex, std::memory_order_release);
        // Only this worker writes its count: a plain store, not a locked increment.
        self.finishedPoints.store(++worker.finishedPoints, std::memory_order_release);
    }

    // Locates q, takes the triangles the subdivision changes and subdivides. False when the
    // worker has to start again (overridden, or the located leaf changed before it was taken);
    // `hint` is then where to locate from.
    bool subdivide(Worker& worker, VertexId q, NodeId& hint) {
        const NodeId leaf = m_walk ? m_triangulator.walk(q, hint == 0 ? worker.recent : hint)
                                   : m_triangulator.locate(q, hint);
        if (!take(worker, leaf)) {
            hint = 0;
            return false;
        }
        if (!m_triangulator.node(leaf).isLeaf()) {
            hint = leaf; // split by another worker between location and taking it
            return false;
        }
        const DagNode& node = m_triangulator.node(leaf);
        const int edge = m_triangulator.edgeContaining(leaf, q);
        // Every triangle whose neighbour links the subdivision rewrites must be held: at
        // most the three neighbours of the leaf and two more beyond a split edge.
        std::array<NodeId, 5> needed{};
        std::size_t neededCount = 0;
        for (int i = 0; i < 3; ++i)
            if (node.link[i] != kNoNode)
                needed[neededCount++] = node.link[i];
        if (edge >= 0) {
            const DagNode& beyond = m_triangulator.node(node.link[edge]);
            if (!take(worker, node.link[edge])) {
                hint = 0;
                return false;
            }
            for (const NodeId n : beyond.link)
                if (n != kNoNode && n != leaf)
                    needed[neededCount++] = n;
        }
        for (const NodeId n : std::span(needed).first(neededCount)) {
            if (!take(worker, n)) {
                hint = 0;
                return false;
            }
        }
        const std::size_t before = worker.pending.size();
        if (edge >= 0)
            m_triangulator.splitEdge(leaf, edge, q, worker.pending, worker.tag);
        else
            m_triangulator.splitTriangle(leaf, q, worker.pending, worker.tag);
        holdCreated(worker, before);
        worker.recent = worker.pending[before].first;
        return true;
    }

    // Lawson's legalisation. The neighbour u across a pending edge of t is read without
    // taking it: t is ours, and every edit that could change u or its link to t (a split or
    // flip of u, which rewrites the links of u's neighbours) must take t first. So u stays a
    // leaf beside t, its corners never change, and the in-circle test is exact. Only a flip
    // takes u and the four triangles around the quadrilateral; most tests flip nothing, and
    // each take saved is a compare-and-swap and a release. When overridden, the unchecked
    // edges are left to the repair (repair_rendezvous.hpp).
    void legalize(Worker& worker, VertexId p) {
        const SymbolicPredicates& predicates = m_triangulator.predicates();
        while (!worker.pending.empty()) {
            const auto [t, pos] = worker.pending.back();
            const DagNode& tNode = m_triangulator.node(t);
            const NodeId u = tNode.link[pos];
            if (u == kNoNode) {
                worker.pending.pop_back();
                continue;
            }
            const DagNode& uNode = m_triangulator.node(u);
            int m = 0;
            while (uNode.loadLink(m) != t) // u's other links may be changing
                ++m;
            if (!predicates.shouldFlip(tNode.v[nextCorner(pos)], tNode.v[previousCorner(pos)], p,
                                       uNode.v[m])) {
                worker.pending.pop_back();
                continue;
            }
            if (!take(worker, u)) {
                deferPending(worker);
                return;
            }
            // The flip rewrites the links of the four triangles around the quadrilateral.
            for (const NodeId n : {tNode.link[nextCorner(pos)], tNode.link[previousCorner(pos)],
                                   uNode.link[nextCorner(m)], uNode.link[previousCorner(m)]}) {
                if (n != kNoNode && !take(worker, n)) {
                    deferPending(worker);
                    return;
                }
            }
            worker.pending.pop_back();
            const std::size_t before = worker.pending.size();
            m_triangulator.flip(t, pos, u, m, worker.pending, worker.tag);
            holdCreated(worker, before);
        }
    }

    // After giving up an attempt to break a deadlock: withdraws the point until the worker
    // it would have waited for has finished its own. Published again at once, the point
    // would keep that worker waiting (it is inside the circles around it), and the deadlock
    // would recur for every triangle that worker still needs (measured: millions of
    // deadlocks in a run on points of one circle).
    //
    // These waits cannot close a cycle: a worker steps aside only for one that is waiting
    // (the deadlock was found along the chain of waits), hence not stepping aside itself,
    // and a worker that stepped aside is waited for by no one: it holds nothing and shows
    // no point. So the last of any cycle's waits would have begun for a worker that was
    // already stepping aside.
    void stepAside(Worker& worker, VertexId q) {
        WorkerSlot& self = m_slots[worker.index];
        self.activePoint.store(kNoVertex, std::memory_order_release);
        const WorkerSlot& blocker = m_slots[worker.backedOffFrom];
        while (blocker.finishedPoints.load(std::memory_order_acquire) ==
                   worker.blockerFinishedPoints &&
               !stopping())
            std::this_thread::yield();
        worker.backedOffFrom = -1;
        self.activePoint.store(q, std::memory_order_release);
    }

    void deferPending(Worker& worker) {
        worker.statistics.deferredEdges += worker.pending.size();
        worker.pending.clear();
    }

    // Nodes the last edit created carry the worker's tag already; remember to free them.
    static void holdCreated(Worker& worker, std::size_t firstNew) {
        for (std::size_t i = firstNew; i < worker.pending.size(); ++i)
            worker.held.push_back(worker.pending[i].first);
    }

    void releaseAll(Worker& worker) {
        if (std::exchange(worker.overridden, false)) {
            for (const NodeId n : worker.held) {
                // A triangle taken over by an overriding worker is no longer ours to free.
                std::uint32_t expected = worker.tag;
                m_triangulator.node(n).owner.compare_exchange_strong(
                    expected, 0, std::memory_order_release, std::memory_order_relaxed);
            }
        } else {
            // Only a worker that was overridden loses triangles (an override is decided
            // while its victim waits, and the victim always sees its flag when the wait
            // ends), so here every triangle is still ours: plain release stores, not a
            // locked read-modify-write each, which would drain the store buffer every time.
            for (const NodeId n : worker.held)
                m_triangulator.node(n).owner.store(0, std::memory_order_release);
        }
        worker.held.clear();
        worker.changedMesh = false;
        ++worker.attempt;
        worker.tag = ownerTag(worker.index, worker.attempt & (~0U >> kWorkerBits));
        m_slots[worker.index].tag.store(worker.tag, std::memory_order_relaxed);
    }

    // Another worker whose point lies strictly inside the circumcircle of `node`, or -1.
    // Points too close to the circle for the floating-point filter count as outside: on
    // near-cocircular data (an arc) the exact test went adaptive on nearly every call and
    // took much of the run (docs/benchmarks.md), and the owner tags protect the triangles
    // either way.
    // From kRegionFilterWorkers on, workers whose region the circumcircle misses are skipped
    // without reading their active point, which another core keeps rewriting. Reading all of
    // them on every take, the method ran slower on 16 threads than on 1 (docs/benchmarks.md).
    int workerInCircle(const Worker& worker, const DagNode& node) const {
        const SymbolicPredicates& predicates = m_triangulator.predicates();
        const bool finite = predicates.isFinite(node.v[0]) && predicates.isFinite(node.v[1]) &&
                            predicates.isFinite(node.v[2]);
        const bool filter = filterByRegion() && finite;
        const Circle circle =
            filter ? Circle::through(predicates.point(node.v[0]), predicates.point(node.v[1]),
                                     predicates.point(node.v[2]))
                   : Circle{};
        for (unsigned k = 0; k < m_slots.size(); ++k) {
            if (k == worker.index || (filter && !circle.mayReach(m_slots[k].region.load())))
                continue;
            const VertexId point = m_slots[k].activePoint.load(std::memory_order_acquire);
            if (point != kNoVertex &&
                predicates.surelyInside(node.v[0], node.v[1], node.v[2], point))
                return static_cast<int>(k);
        }
        return -1;
    }

    // Takes triangle t for the worker. False when the worker was overridden meanwhile (it
    // must give up what it holds) or the run is stopping.
    bool take(Worker& worker, NodeId t) {
        DagNode& node = m_triangulator.node(t);
        for (;;) {
            if (stopping())
                return false;
            std::uint32_t owner = node.owner.load(std::memory_order_acquire);
            if (owner == worker.tag)
                return true;
            int blocker = holderOf(owner);
            if (owner == 0) {
                blocker = workerInCircle(worker, node);
                if (blocker < 0) {
                    if (node.owner.compare_exchange_strong(owner, worker.tag,
                                                           std::memory_order_acq_rel)) {
                        worker.held.push_back(t);
                        return true;
                    }
                    continue;
                }
            }
            std::uint32_t overriddenTag = 0;
            switch (waitFor(worker, blocker, t, overriddenTag)) {
            case WaitOutcome::Retry:
                continue;
            case WaitOutcome::Aborted:
                worker.overridden = true;
                return false;
            case WaitOutcome::BackOff:
                return false; // waitFor recorded whom to step aside for
            case WaitOutcome::Override:
                // Ignore the circum-circle test; take the triangle even from the blocker's
                // overridden attempt: it is waiting and will give up when it sees its flag.
                owner = node.owner.load(std::memory_order_acquire);
                if ((owner == 0 || owner == overriddenTag) &&
                    node.owner.compare_exchange_strong(owner, worker.tag,
                                                       std::memory_order_acq_rel)) {
                    worker.held.push_back(t);
                    return true;
                }
                continue;
            }
        }
    }

    // Called before an override takes its first triangle (repair_rendezvous.hpp).
    void requestRepair() {
        NodeId lowest = kNoNode;
        for (const WorkerSlot& slot : m_slots)
            lowest = std::min(lowest, slot.lowestNewNode.load(std::memory_order_relaxed));
        m_repair.request(lowest);
    }

    bool stillBlocked(const DagNode& node, int blocker, VertexId watchedPoint) const {
        if (holderOf(node.owner.load(std::memory_order_acquire)) == blocker)
            return true;
        return watchedPoint != kNoVertex &&
               m_slots[blocker].activePoint.load(std::memory_order_acquire) == watchedPoint &&
               m_triangulator.predicates().surelyInside(node.v[0], node.v[1], node.v[2],
                                                        watchedPoint);
    }

    // Waits while `blocker` keeps t. On Override, `overriddenTag` is the blocker's tag for
    // the attempt overridden.
    WaitOutcome waitFor(Worker& worker, int blocker, NodeId t, std::uint32_t& overriddenTag) {
        WorkerSlot& self = m_slots[worker.index];
        {
            // Deadlock detection: does the chain of waits from the blocker lead back here?
            const std::lock_guard lock(m_waitMutex);
            int next = blocker;
            for (std::size_t steps = 0;
                 next >= 0 && next != static_cast<int>(worker.index) && steps <= m_slots.size();
                 ++steps)
                next = m_slots[next].waitingFor;
            if (next == static_cast<int>(worker.index)) {
                // A worker that has changed nothing yet breaks the cycle by giving up its
                // own attempt: no edge is left unchecked, and no repair is needed.
                if (!worker.changedMesh) {
                    ++worker.statistics.backOffs;
                    worker.backedOffFrom = blocker;
                    // The blocker is waiting: its count cannot change before the wait ends.
                    worker.blockerFinishedPoints =
                        m_slots[blocker].finishedPoints.load(std::memory_order_relaxed);
                    return WaitOutcome::BackOff;
                }
                // The blocker is waiting, so its attempt (and tag) cannot change until it
                // sees the flag and gives up.
                overriddenTag = m_slots[blocker].tag.load(std::memory_order_relaxed);
                requestRepair();
                m_slots[blocker].overridden.store(true, std::memory_order_release);
                ++worker.statistics.overrides;
                return WaitOutcome::Override;
            }
            self.waitingFor = blocker;
        }
        ++worker.statistics.waits;
        const DagNode& node = m_triangulator.node(t);
        const VertexId watched = m_slots[blocker].activePoint.load(std::memory_order_acquire);
        while (stillBlocked(node, blocker, watched) &&
               !self.overridden.load(std::memory_order_acquire) && !stopping())
            std::this_thread::yield();
        const std::lock_guard lock(m_waitMutex);
        self.waitingFor = -1;
        return self.overridden.exchange(false, std::memory_order_acq_rel) ? WaitOutcome::Aborted
                                                                          : WaitOutcome::Retry;
    }

    DagTriangulator& m_triangulator;
    std::span<const VertexId> m_order;
    std::span<const std::size_t> m_roundStarts;
    std::vector<WorkerSlot> m_slots;
    /// Locate by walking (DagTriangulator::walk) instead of descending the DAG.
    bool m_walk;
    std::atomic<std::size_t> m_inserted{0};
    std::atomic<bool> m_stop{false};
    std::atomic<bool> m_cancelled{false};
    std::mutex m_waitMutex;
    std::mutex m_failureMutex;
    std::exception_ptr m_failure;
    std::mutex m_statisticsMutex;
    CircumcircleStatistics m_statistics;
    RepairRendezvous m_repair;
};

} // namespace

CircumcircleStatistics insertWithCircumcircleMethod(DagTriangulator& triangulator,
                                                    std::span<const VertexId> order,
                                                    std::span<const std::size_t> roundStarts,
                                                    unsigned workers, bool walk,
                                                    const ProgressCallback& progress) {
    workers = std::clamp(workers, 1U, kMaxWorkers);
    CircumcircleRun run(triangulator, order, roundStarts, workers, walk);
    // Every worker on a thread of its own; the calling thread watches.
    runWatched(
        workers, [&run](unsigned index) { run.work(index); },
        [&run, &progress] { return run.report(progress); }, [&run] { run.requestStop(); });
    run.finish();
    return run.statistics();
}

} // namespace terratin::detail

#include "circumcircle_insertion.hpp"

#include "../parallel/watched_threads.hpp"
#include "circumcircle_worker.hpp"
#include "owner_tag.hpp"
#include "repair_rendezvous.hpp"
#include "triangle_claims.hpp"

#include "terratin/error.hpp"

#include <algorithm>
#include <array>
#include <atomic>
#include <exception>
#include <mutex>
#include <span>
#include <utility>

namespace terratin::detail {

namespace {

// Workers add to the shared count of insertions (for the watching thread's progress
// reports) once per this many of their own.
constexpr std::size_t kCountBatch = 4096;

// The workers' run: each inserts its share of every round, one point after the other, taking
// what it changes through m_claims. On a cache line of its own: it lives on the calling
// thread's stack, whose other writes would otherwise make every worker's read of the fields
// below a cache miss (a profile of `take` found it in the load of the triangulator;
// docs/benchmarks.md).
class alignas(64) CircumcircleRun {
public:
    CircumcircleRun(DagTriangulator& triangulator, std::span<const VertexId> order,
                    std::span<const std::size_t> roundStarts, unsigned workers, bool walk)
        : m_triangulator(&triangulator), m_order(order), m_roundStarts(roundStarts), m_walk(walk),
          m_repair(triangulator, workers), m_claims(triangulator, workers, m_repair) {}

    void work(WorkerIndex index) {
        Worker worker = m_claims.startWorker(index);
        try {
            for (std::size_t round = 0; round < m_roundStarts.size() && !stopping(); ++round)
                insertShare(worker, round);
        } catch (...) {
            fail(std::current_exception());
        }
        m_claims.releaseAll(worker);
        m_claims.withdrawPoint(worker);
        try {
            m_repair.leave(); // may run a repair, which allocates
        } catch (...) {
            fail(std::current_exception());
        }
        addStatistics(worker.statistics);
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
        m_claims.requestStop();
        m_repair.stop();
    }

private:
    [[nodiscard]] bool stopping() const { return m_claims.stopping(); }

    // Inserts the worker's contiguous share of the round's points.
    void insertShare(Worker& worker, std::size_t round) {
        const std::size_t workers = m_claims.workers();
        const std::size_t roundBegin = m_roundStarts[round];
        const std::size_t roundEnd =
            round + 1 < m_roundStarts.size() ? m_roundStarts[round + 1] : m_order.size();
        const std::size_t length = roundEnd - roundBegin;
        const std::size_t begin = roundBegin + length * worker.index / workers;
        const std::size_t end = roundBegin + length * (worker.index + 1) / workers;
        if (m_claims.filterByRegion())
            m_claims.publishRegion(worker.index, m_order.subspan(begin, end - begin));
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

    void insertPoint(Worker& worker, VertexId q) {
        m_claims.showPoint(worker, q);
        NodeId hint = 0;
        while (!subdivide(worker, q, hint)) {
            m_claims.releaseAll(worker);
            if (worker.backOff)
                m_claims.stepAside(worker, q);
            if (stopping())
                return;
        }
        worker.changedMesh = true;
        legalize(worker, q);
        m_claims.releaseAll(worker);
        m_claims.withdrawPoint(worker);
        ++worker.finishedPoints;
        m_claims.publishFinishedPoints(worker);
    }

    // Locates q, takes the triangles the subdivision changes and subdivides. False when the
    // worker has to start again (overridden, backed off, or the located leaf changed before
    // it was taken); `hint` is then where to locate from.
    bool subdivide(Worker& worker, VertexId q, NodeId& hint) {
        const NodeId leaf = m_walk ? m_triangulator->walk(q, hint == 0 ? worker.recent : hint)
                                   : m_triangulator->locate(q, hint);
        if (!m_claims.take(worker, leaf)) {
            hint = 0;
            return false;
        }
        if (!m_triangulator->node(leaf).isLeaf()) {
            hint = leaf; // split by another worker between location and taking it
            return false;
        }
        const DagNode& node = m_triangulator->node(leaf);
        const int edge = m_triangulator->edgeContaining(leaf, q);
        // Every triangle whose neighbour links the subdivision rewrites must be held: at
        // most the three neighbours of the leaf and two more beyond a split edge.
        std::array<NodeId, 5> needed{};
        std::size_t neededCount = 0;
        for (int i = 0; i < 3; ++i)
            if (node.link[i] != kNoNode)
                needed[neededCount++] = node.link[i];
        if (edge >= 0) {
            const DagNode& beyond = m_triangulator->node(node.link[edge]);
            if (!m_claims.take(worker, node.link[edge])) {
                hint = 0;
                return false;
            }
            for (const NodeId n : beyond.link)
                if (n != kNoNode && n != leaf)
                    needed[neededCount++] = n;
        }
        for (const NodeId n : std::span(needed).first(neededCount)) {
            if (!m_claims.take(worker, n)) {
                hint = 0;
                return false;
            }
        }
        const std::size_t before = worker.pending.size();
        if (edge >= 0)
            m_triangulator->splitEdge(leaf, edge, q, worker.pending, worker.tag.word());
        else
            m_triangulator->splitTriangle(leaf, q, worker.pending, worker.tag.word());
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
        const SymbolicPredicates& predicates = m_triangulator->predicates();
        while (!worker.pending.empty()) {
            const auto [t, pos] = worker.pending.back();
            const DagNode& tNode = m_triangulator->node(t);
            const NodeId u = tNode.link[pos];
            if (u == kNoNode) {
                worker.pending.pop_back();
                continue;
            }
            const DagNode& uNode = m_triangulator->node(u);
            // u's other links may be changing.
            const int m = uNode.linkIndexOf<LinkRead::Published>(t);
            if (!predicates.shouldFlip(tNode.v[nextCorner(pos)], tNode.v[previousCorner(pos)], p,
                                       uNode.v[m])) {
                worker.pending.pop_back();
                continue;
            }
            if (!m_claims.take(worker, u)) {
                deferPending(worker);
                return;
            }
            // The flip rewrites the links of the four triangles around the quadrilateral.
            for (const NodeId n : {tNode.link[nextCorner(pos)], tNode.link[previousCorner(pos)],
                                   uNode.link[nextCorner(m)], uNode.link[previousCorner(m)]}) {
                if (n != kNoNode && !m_claims.take(worker, n)) {
                    deferPending(worker);
                    return;
                }
            }
            worker.pending.pop_back();
            const std::size_t before = worker.pending.size();
            m_triangulator->flip(t, pos, u, m, worker.pending, worker.tag.word());
            holdCreated(worker, before);
        }
    }

    static void deferPending(Worker& worker) {
        worker.statistics.deferredEdges += worker.pending.size();
        worker.pending.clear();
    }

    // Nodes the last edit created carry the worker's tag already; remember to free them.
    static void holdCreated(Worker& worker, std::size_t firstNew) {
        for (std::size_t i = firstNew; i < worker.pending.size(); ++i)
            worker.held.push_back(worker.pending[i].first);
    }

    void fail(std::exception_ptr failure) {
        {
            const std::lock_guard lock(m_failureMutex);
            if (!m_failure)
                m_failure = std::move(failure);
        }
        requestStop();
    }

    void addStatistics(const CircumcircleStatistics& own) {
        const std::lock_guard lock(m_statisticsMutex);
        m_statistics.waits += own.waits;
        m_statistics.overrides += own.overrides;
        m_statistics.backOffs += own.backOffs;
        m_statistics.deferredEdges += own.deferredEdges;
    }

    DagTriangulator* m_triangulator;
    std::span<const VertexId> m_order;
    std::span<const std::size_t> m_roundStarts;
    /// Locate by walking (DagTriangulator::walk) instead of descending the DAG.
    bool m_walk;
    RepairRendezvous m_repair;
    TriangleClaims m_claims;
    std::atomic<std::size_t> m_inserted{0};
    std::atomic<bool> m_cancelled{false};
    std::mutex m_failureMutex;
    std::exception_ptr m_failure;
    std::mutex m_statisticsMutex;
    CircumcircleStatistics m_statistics;
};

} // namespace

CircumcircleStatistics insertWithCircumcircleMethod(DagTriangulator& triangulator,
                                                    std::span<const VertexId> order,
                                                    std::span<const std::size_t> roundStarts,
                                                    unsigned workers, bool walk,
                                                    const ProgressCallback& progress) {
    workers = std::clamp(workers, 1U, OwnerTag::kMaxWorkers);
    CircumcircleRun run(triangulator, order, roundStarts, workers, walk);
    // Every worker on a thread of its own; the calling thread watches.
    runWatched(
        workers, [&run](WorkerIndex index) { run.work(index); },
        [&run, &progress] { return run.report(progress); }, [&run] { run.requestStop(); });
    run.finish();
    return run.statistics();
}

} // namespace terratin::detail

#include "batch_insertion.hpp"

#include "../parallel/watched_threads.hpp"
#include "bounded_queue.hpp"

#include "terratin/error.hpp"

#include <algorithm>
#include <atomic>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace terratin::detail {

namespace {

// Searchers claim this many consecutive points of the (spatially coherent) insertion order
// at a time: few enough to keep the threads' work balanced, many enough that the shared
// cursor is not contended and consecutive locations reuse the same DAG paths in cache.
constexpr std::size_t kClaimedPoints = 64;

struct Located {
    VertexId vertex;
    NodeId node;
};

// State shared by the searching threads and the specialised thread. Aligned to a cache line,
// as CircumcircleRun is: it lives on the specialised thread's stack.
class alignas(64) BatchRun {
public:
    BatchRun(DagTriangulator& triangulator, std::span<const VertexId> order,
             const BatchSettings& settings)
        : m_triangulator(triangulator), m_order(order), m_settings(settings),
          m_queue(settings.queueLength) {}

    void search() {
        NodeId previous = 0; // where the previous point was found
        try {
            for (;;) {
                const std::size_t begin =
                    m_cursor.fetch_add(kClaimedPoints, std::memory_order_relaxed);
                if (begin >= m_order.size() || stopping())
                    return;
                const std::size_t end = std::min(begin + kClaimedPoints, m_order.size());
                for (std::size_t i = begin; i < end; ++i) {
                    const VertexId q = m_order[i];
                    previous = m_settings.walk ? m_triangulator.walk(q, previous)
                                               : m_triangulator.locate(q);
                    if (!deliver({q, previous}, m_settings.searchersHelpWhenFull))
                        return;
                }
            }
        } catch (...) {
            fail(std::current_exception());
        }
    }

    // The specialised thread: completes each location, subdivides and legalises. Publishes
    // its count for the watching thread's progress reports.
    void insertAll() {
        for (std::size_t done = 0; done < m_order.size(); ++done) {
            Located item{};
            while (!m_queue.tryPop(item)) {
                if (stopping())
                    return;
                std::this_thread::yield();
            }
            if (stopping())
                return;
            try {
                m_triangulator.insertAtLeaf(m_triangulator.locate(item.vertex, item.node),
                                            item.vertex);
            } catch (...) {
                fail(std::current_exception());
                return;
            }
            m_inserted.store(done + 1, std::memory_order_relaxed);
        }
    }

    // The watching thread's report; false once the callback asked to stop.
    bool report(const ProgressCallback& progress) {
        const std::size_t done = m_inserted.load(std::memory_order_relaxed);
        if (!progress || progress(static_cast<double>(done) / static_cast<double>(m_order.size()),
                                  "triangulating"))
            return true;
        m_cancelled = true; // read after the threads have joined
        return false;
    }

    void stop() { m_stop.store(true, std::memory_order_release); }

    void rethrowFailure() {
        if (m_failure)
            std::rethrow_exception(m_failure);
        if (m_cancelled)
            throw Cancelled("Triangulator: cancelled");
    }

    [[nodiscard]] std::size_t helpedLocations() const {
        return m_helped.load(std::memory_order_relaxed);
    }

private:
    [[nodiscard]] bool stopping() const { return m_stop.load(std::memory_order_acquire); }

    // Pushes `item`, waiting (or helping) while the queue is full; false when the run stops.
    bool deliver(Located item, bool mayHelp) {
        while (!m_queue.tryPush(item)) {
            if (stopping())
                return false;
            if (mayHelp && helpSpecialisedThread())
                continue;
            std::this_thread::yield();
        }
        return true;
    }

    // Takes the oldest queued element, completes its location and queues it again. False
    // when there was nothing to pop or its location was already complete: re-queueing it
    // would only rotate the queue, so the caller should wait instead.
    bool helpSpecialisedThread() {
        Located other{};
        if (!m_queue.tryPop(other))
            return false;
        const NodeId located = m_triangulator.locate(other.vertex, other.node);
        const bool advanced = located != other.node;
        other.node = located;
        if (advanced)
            m_helped.fetch_add(1, std::memory_order_relaxed);
        // The slot just freed may be taken by another searcher: wait for one like any push,
        // without helping again (that could recurse without bound).
        return deliver(other, false) && advanced;
    }

    void fail(std::exception_ptr error) {
        {
            const std::lock_guard lock(m_failureMutex);
            if (!m_failure)
                m_failure = std::move(error);
        }
        stop();
    }

    DagTriangulator& m_triangulator;
    std::span<const VertexId> m_order;
    const BatchSettings& m_settings;
    BoundedQueue<Located> m_queue;
    std::atomic<std::size_t> m_cursor{0};
    std::atomic<std::size_t> m_inserted{0};
    std::atomic<bool> m_stop{false};
    std::atomic<std::size_t> m_helped{0};
    bool m_cancelled = false;
    std::mutex m_failureMutex;
    std::exception_ptr m_failure;
};

} // namespace

BatchStatistics insertWithBatchMethod(DagTriangulator& triangulator,
                                      std::span<const VertexId> order,
                                      const BatchSettings& settings,
                                      const ProgressCallback& progress) {
    BatchRun run(triangulator, order, settings);
    // Thread 0 is the specialised one, the others search; the calling thread watches.
    const unsigned searchers = std::max(1U, settings.searchers);
    runWatched(
        searchers + 1,
        [&run](unsigned index) {
            if (index == 0) {
                run.insertAll();
                run.stop(); // releases searchers waiting on a full queue after a failure
            } else {
                run.search();
            }
        },
        [&run, &progress] { return run.report(progress); }, [&run] { run.stop(); });
    run.rethrowFailure();
    return {run.helpedLocations()};
}

} // namespace terratin::detail

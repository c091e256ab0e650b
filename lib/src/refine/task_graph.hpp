#pragma once
/// @file
/// Tasks with dependencies, run on a RoundWorkers team: the strips and pairs of strips of one
/// refinement level (planLevel in level_tasks.hpp says which waits for which).
///
/// A barrier after every step (all strips, then the pairs of one parity, then the other)
/// leaves threads idle while the last task of a step runs, and a thread the hypervisor
/// pauses holds up the others at every barrier. With dependencies instead, a pair starts as
/// soon as its two strips are done, while other strips still run. The dependencies alone fix
/// what each task sees, so the result does not depend on the order the threads take tasks in.

#include "../parallel/round_workers.hpp"

#include <atomic>
#include <condition_variable>
#include <cstddef>
#include <exception>
#include <mutex>
#include <set>
#include <vector>

namespace terratin::detail {

class TaskGraph {
public:
    /// Adds a task and returns its number; ready tasks start lowest number first.
    std::size_t add() {
        m_successors.emplace_back();
        m_waitingFor.push_back(0);
        return m_successors.size() - 1;
    }
    /// `task` starts only after `dependency` has finished (added before it or not).
    void after(std::size_t task, std::size_t dependency) {
        m_successors[dependency].push_back(task);
        ++m_waitingFor[task];
    }
    [[nodiscard]] std::size_t size() const { return m_successors.size(); }

    /// Runs body(task, worker) for every task on `workers`, each once, respecting the
    /// dependencies. Once `stop` is set no task starts; those running finish. Rethrows the
    /// first exception a task threw, after the running tasks have finished.
    template <class Body>
    void run(RoundWorkers& workers, const std::atomic<bool>& stop, Body&& body) {
        std::vector<std::size_t> waitingFor = m_waitingFor;
        std::set<std::size_t> ready;
        for (std::size_t task = 0; task < waitingFor.size(); ++task)
            if (waitingFor[task] == 0)
                ready.insert(task);
        std::size_t finished = 0;
        bool failed = false;
        std::mutex mutex;
        std::condition_variable changed;
        workers.run([&](unsigned worker) {
            std::unique_lock lock(mutex);
            for (;;) {
                changed.wait(lock, [&] {
                    return !ready.empty() || finished == waitingFor.size() || failed ||
                           stop.load(std::memory_order_relaxed);
                });
                if (ready.empty() || failed || stop.load(std::memory_order_relaxed))
                    return; // all done, or nothing more may start
                const std::size_t task = *ready.begin();
                ready.erase(ready.begin());
                lock.unlock();
                try {
                    body(task, worker);
                } catch (...) {
                    lock.lock();
                    failed = true;
                    changed.notify_all();
                    throw; // RoundWorkers keeps the first exception
                }
                lock.lock();
                ++finished;
                for (const std::size_t next : m_successors[task])
                    if (--waitingFor[next] == 0)
                        ready.insert(next);
                changed.notify_all();
            }
        });
    }

private:
    std::vector<std::vector<std::size_t>> m_successors;
    std::vector<std::size_t> m_waitingFor;
};

} // namespace terratin::detail

#pragma once
/// @file
/// A fixed team of threads that runs one task per round, for the refiner's many short
/// parallel rounds (hundreds of microseconds each): starting threads every round would cost
/// tens of microseconds, so the team waits at a barrier between rounds instead.

#include <barrier>
#include <cstddef>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>
#include <utility>
#include <vector>

namespace terratin::detail {

class RoundWorkers {
public:
    /// `threads` in all, the calling thread included (at least 1).
    explicit RoundWorkers(unsigned threads)
        : m_threads(threads == 0 ? 1 : threads), m_start(m_threads), m_end(m_threads) {
        m_others.reserve(m_threads - 1);
        for (unsigned i = 1; i < m_threads; ++i)
            m_others.emplace_back([this, i] { loop(i); });
    }
    ~RoundWorkers() {
        m_stop = true; // published by the barrier
        m_start.arrive_and_wait();
        m_others.clear(); // joins
    }
    RoundWorkers(const RoundWorkers&) = delete;
    RoundWorkers& operator=(const RoundWorkers&) = delete;

    [[nodiscard]] unsigned size() const { return m_threads; }

    /// Runs task(worker) on every worker (0 = the calling thread) and returns when all have
    /// finished; rethrows the first exception a worker threw.
    void run(const std::function<void(unsigned)>& task) {
        if (m_threads == 1) {
            task(0);
            return;
        }
        m_task = &task;
        m_start.arrive_and_wait();
        runGuarded(0);
        m_end.arrive_and_wait();
        m_task = nullptr;
        if (m_failure)
            std::rethrow_exception(std::exchange(m_failure, nullptr));
    }

private:
    void loop(unsigned index) {
        for (;;) {
            m_start.arrive_and_wait();
            if (m_stop)
                return;
            runGuarded(index);
            m_end.arrive_and_wait();
        }
    }
    void runGuarded(unsigned index) {
        try {
            (*m_task)(index);
        } catch (...) {
            const std::lock_guard lock(m_failureMutex);
            if (!m_failure)
                m_failure = std::current_exception();
        }
    }

    unsigned m_threads;
    std::barrier<> m_start;
    std::barrier<> m_end;
    const std::function<void(unsigned)>* m_task = nullptr;
    bool m_stop = false;
    std::mutex m_failureMutex;
    std::exception_ptr m_failure;
    std::vector<std::jthread> m_others;
};

} // namespace terratin::detail

#pragma once
/// @file
/// A fixed team of threads that runs one task per round, for the refiner's parallel steps
/// (the first scans, then the strips of each level: dozens of rounds, some of them short).
///
/// Starting threads every round would cost tens of microseconds, so the team stays. Between
/// rounds the threads spin briefly before they sleep: the calling thread's sequential work
/// between two rounds is often shorter than waking a sleeping thread, which on a virtual
/// machine can take as long as a short round itself. A thread that finds no
/// round after the spin sleeps on the round counter (std::atomic::wait), so the team costs
/// nothing while the caller does something else.

#include <atomic>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>
#include <utility>
#include <vector>

namespace terratin::detail {

/// One iteration of a spin-wait: tells the core (and a hypervisor) that this thread waits.
inline void spinPause() {
#if defined(__x86_64__) || defined(__i386__)
    __builtin_ia32_pause();
#elif defined(__aarch64__)
    asm volatile("yield");
#endif
}

/// Waits until `value` differs from `old`: spins for up to `spin`, then sleeps on it.
template <class T>
T awaitChange(const std::atomic<T>& value, T old, std::chrono::microseconds spin) {
    const auto deadline = std::chrono::steady_clock::now() + spin;
    for (unsigned i = 1;; ++i) {
        const T now = value.load(std::memory_order_acquire);
        if (now != old)
            return now;
        spinPause();
        // A pause takes from 10 to 150 cycles depending on the processor: spin by the clock.
        if (i % 16 == 0 && std::chrono::steady_clock::now() > deadline)
            break;
    }
    value.wait(old, std::memory_order_acquire);
    return value.load(std::memory_order_acquire);
}

class RoundWorkers {
public:
    /// `threads` in all, the calling thread included (at least 1).
    explicit RoundWorkers(unsigned threads) : m_threads(threads == 0 ? 1 : threads) {
        m_others.reserve(m_threads - 1);
        for (unsigned i = 1; i < m_threads; ++i)
            m_others.emplace_back([this, i] { loop(i); });
    }
    ~RoundWorkers() {
        m_stop.store(true, std::memory_order_relaxed);
        m_round.fetch_add(1, std::memory_order_release);
        m_round.notify_all();
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
        m_running.store(m_threads - 1, std::memory_order_relaxed);
        m_round.fetch_add(1, std::memory_order_release); // publishes m_task
        m_round.notify_all();
        runGuarded(0);
        for (unsigned left = m_running.load(std::memory_order_acquire); left != 0;)
            left = awaitChange(m_running, left, kSpins);
        m_task = nullptr;
        if (m_failure)
            std::rethrow_exception(std::exchange(m_failure, nullptr));
    }

private:
    /// Spinning before a thread sleeps: longer than the caller's work between two rounds.
    static constexpr std::chrono::microseconds kSpins{300};

    void loop(unsigned index) {
        std::uint64_t seen = 0;
        for (;;) {
            seen = awaitChange(m_round, seen, kSpins);
            if (m_stop.load(std::memory_order_relaxed))
                return;
            runGuarded(index);
            if (m_running.fetch_sub(1, std::memory_order_acq_rel) == 1)
                m_running.notify_one();
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
    /// Incremented by the caller to start a round (and to stop the team).
    std::atomic<std::uint64_t> m_round{0};
    /// Workers other than the caller still running the current round.
    std::atomic<unsigned> m_running{0};
    std::atomic<bool> m_stop{false};
    const std::function<void(unsigned)>* m_task = nullptr;
    std::mutex m_failureMutex;
    std::exception_ptr m_failure;
    std::vector<std::jthread> m_others;
};

} // namespace terratin::detail

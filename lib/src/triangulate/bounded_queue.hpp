#pragma once
/// @file
/// Bounded multi-producer multi-consumer queue (D. Vyukov's array queue): each cell carries a
/// sequence number telling producers and consumers whose turn it is, so a push or a pop is one
/// compare-and-swap on a shared position plus one release store — the "short critical
/// section" of Kohout & Kolingerova's batch method, without a mutex.

#include <atomic>
#include <bit>
#include <cstddef>
#include <memory>

namespace terratin::detail {

template <class T> class BoundedQueue {
public:
    /// Capacity rounded up to a power of two (at least 2).
    explicit BoundedQueue(std::size_t capacity)
        : m_capacity(std::bit_ceil(capacity < 2 ? std::size_t{2} : capacity)),
          m_cells(new Cell[m_capacity]) {
        for (std::size_t i = 0; i < m_capacity; ++i)
            m_cells[i].sequence.store(i, std::memory_order_relaxed);
    }

    [[nodiscard]] std::size_t capacity() const { return m_capacity; }

    /// False when the queue is full.
    bool tryPush(const T& value) {
        std::size_t position = m_tail.load(std::memory_order_relaxed);
        for (;;) {
            Cell& cell = m_cells[position & (m_capacity - 1)];
            const std::size_t sequence = cell.sequence.load(std::memory_order_acquire);
            const auto lag = static_cast<std::ptrdiff_t>(sequence - position);
            if (lag == 0) {
                if (m_tail.compare_exchange_weak(position, position + 1,
                                                 std::memory_order_relaxed)) {
                    cell.value = value;
                    cell.sequence.store(position + 1, std::memory_order_release);
                    return true;
                }
            } else if (lag < 0) {
                return false;
            } else {
                position = m_tail.load(std::memory_order_relaxed);
            }
        }
    }

    /// False when the queue is empty.
    bool tryPop(T& value) {
        std::size_t position = m_head.load(std::memory_order_relaxed);
        for (;;) {
            Cell& cell = m_cells[position & (m_capacity - 1)];
            const std::size_t sequence = cell.sequence.load(std::memory_order_acquire);
            const auto lag = static_cast<std::ptrdiff_t>(sequence - (position + 1));
            if (lag == 0) {
                if (m_head.compare_exchange_weak(position, position + 1,
                                                 std::memory_order_relaxed)) {
                    value = cell.value;
                    cell.sequence.store(position + m_capacity, std::memory_order_release);
                    return true;
                }
            } else if (lag < 0) {
                return false;
            } else {
                position = m_head.load(std::memory_order_relaxed);
            }
        }
    }

private:
    struct Cell {
        std::atomic<std::size_t> sequence;
        T value;
    };
    // Producers and consumers hammer different positions: keep them on separate cache lines.
    static constexpr std::size_t kCacheLine = 64;

    std::size_t m_capacity;
    std::unique_ptr<Cell[]> m_cells;
    alignas(kCacheLine) std::atomic<std::size_t> m_tail{0};
    alignas(kCacheLine) std::atomic<std::size_t> m_head{0};
};

} // namespace terratin::detail

#pragma once
// How a constraint insertion sees a cancel. Its inserters count their steps (a polyline point
// located and inserted, a piece of a segment inserted: microseconds each, a piece at most a walk
// and its flips across the mesh) and call a check every kStepsPerPoll steps, which throws
// Cancelled to stop. The calling thread's inserter checks the progress callback; a zone's
// inserter, on a thread of its own, checks a flag that the calling thread sets when the callback
// asks to stop: the callback is only ever called from the calling thread.

#include <cstdint>
#include <functional>
#include <utility>

namespace terratin::detail {

/// Steps between two checks: a check (a progress callback: an atomic load, a line printed now
/// and then) costs less than a step, and 64 steps take well under a few milliseconds.
inline constexpr std::uint32_t kStepsPerPoll = 64;

class InsertionPoll {
public:
    InsertionPoll() = default;
    /// `check` throws (Cancelled) to stop the insertion.
    explicit InsertionPoll(std::function<void()> check) : m_check(std::move(check)) {}

    /// One step done: every kStepsPerPoll-th calls the check.
    void step() {
        if (m_check && ++m_steps == kStepsPerPoll) {
            m_steps = 0;
            m_check();
        }
    }

private:
    std::function<void()> m_check;
    std::uint32_t m_steps = 0;
};

} // namespace terratin::detail

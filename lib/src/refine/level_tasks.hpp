#pragma once
/// @file
/// The tasks of one refinement level and the order they may run in: every strip, then every
/// pair of neighbouring strips, as a TaskGraph for the refiner's workers. docs/algorithms.md
/// ("Parallel, by strips and levels") tells why pairs wait for what they wait for.

#include "refine_mesh.hpp"
#include "task_graph.hpp"

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace terratin::detail {

/// A task of a level: strip k alone, or the pair of strips k and k + 1.
class LevelTask {
public:
    [[nodiscard]] static LevelTask strip(std::uint8_t k) { return {k, false}; }
    [[nodiscard]] static LevelTask pair(std::uint8_t k) { return {k, true}; }

    [[nodiscard]] bool isPair() const { return m_pair; }
    /// The strip, or the pair's first strip.
    [[nodiscard]] std::uint8_t first() const { return m_first; }
    /// The strips its insertions may touch.
    [[nodiscard]] StripRange strips() const {
        return {m_first, static_cast<std::uint8_t>(m_pair ? m_first + 1 : m_first)};
    }
    friend bool operator==(LevelTask a, LevelTask b) = default;

private:
    LevelTask(std::uint8_t first, bool pair) : m_first(first), m_pair(pair) {}

    std::uint8_t m_first;
    bool m_pair;
};

/// The tasks of a level: graph task t is tasks[t].
struct LevelPlan {
    TaskGraph graph;
    std::vector<LevelTask> tasks;
};

/// The plan of a level of `stripCandidates.size()` strips (at least 1; candidates queued in
/// each strip). A pair starts after its two strips; a pair starting at an odd strip also after
/// the pairs beside it, which share its strips. Ready tasks start in this order: the strips
/// with the most candidates first (ties: the lower strip), so that the last ones taken are
/// short, then the pairs starting at an even strip, then the odd ones.
[[nodiscard]] LevelPlan planLevel(std::span<const std::size_t> stripCandidates);

} // namespace terratin::detail

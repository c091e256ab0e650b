#pragma once
/// @file
/// The refiner's levels of error and each task's share of a limit: when a level stops, and
/// how many points a strip or a pair may insert in it. The whole story of the levels is in
/// docs/algorithms.md ("The refiner", "Parallel, by strips and levels").

#include <cstddef>
#include <limits>
#include <optional>

namespace terratin::detail {

/// The priority of a triangle over an open hole's cell and a valid non-vertex cell: refined
/// before any error.
inline constexpr double kHolePriority = std::numeric_limits<double>::infinity();

/// Each level goes down to this fraction of the highest error left. Closer to 1 follows the
/// greedy order more closely across strips, at the cost of more levels (each ends with a
/// sequential step and a barrier).
inline constexpr double kLevelRatio = 0.5;

/// Errors below this fraction of the first (largest) error end the levels: the last level
/// goes straight to the target. They are a nanometre per metre of relief, too small for the
/// order across strips to matter, and on a grid used whole (no target: every cell goes in) they
/// are mostly the rounding of the interpolation (~1e-14 m): without the floor, the halving
/// would spend a level (a sequential step and a barrier) on each octave of that noise (test
/// RefineLevels.PlaneUsedWhole_SkipsTheLevelsOfRoundingNoise). It bounds the levels above it
/// to about log2(1e9) = 30.
inline constexpr double kNegligibleErrorFraction = 1e-9;

/// Under limits, tasks get a share of what is left per level until it is less than this
/// many points per strip; then one thread finishes exactly (finishesExactly).
inline constexpr std::size_t kMinStripQuota = 64;

/// Points a task may insert in a level when none is limited.
inline constexpr std::size_t kNoQuota = std::numeric_limits<std::size_t>::max();

/// The level below `top`, the highest priority queued: a fraction kLevelRatio of it, or
/// `threshold` (the target, -1 to use every cell) when that is not above both the target and
/// kNegligibleErrorFraction of `firstPriority`, the highest error once the hull was scanned
/// and the holes' candidates inserted (>= 0). The holes' candidates (top == kHolePriority)
/// make a level of their own. One strip (`strips` == 1) is plain greedy insertion: a single level
/// down to the target.
[[nodiscard]] double levelBelow(double top, double threshold, double firstPriority,
                                std::size_t strips);

/// The points a TIN of `points` vertices and `triangles` triangles may still take under the
/// limits (RefineOptions::maxPoints, maxTriangles; each point inserted adds two triangles),
/// kNoQuota without one. The refiner's rule, which the completion of a constrained TIN
/// (cell_completion.hpp) follows too.
[[nodiscard]] std::size_t pointsUnderLimits(std::optional<std::size_t> maxPoints,
                                            std::optional<std::size_t> maxTriangles,
                                            std::size_t points, std::size_t triangles);

/// Whether `left` points (kNoQuota without a limit) are too few to share among `strips`: one
/// thread then finishes in global priority order and stops exactly at the limit.
[[nodiscard]] bool finishesExactly(std::size_t left, std::size_t strips);

/// The points each task of a level (a strip or a pair) may insert when `left` may still go
/// in: 1 / (2 strips) of it, so that all tasks together stay within it (kNoQuota without a
/// limit).
[[nodiscard]] std::size_t taskQuota(std::size_t left, std::size_t strips);

} // namespace terratin::detail

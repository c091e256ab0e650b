#pragma once
/// @file
/// The vertices a tile border gets, which keep tiles seam-free: chosen once from that
/// border's cells alone, so that the two tiles sharing it put exactly the same vertices on it.

#include <cstdint>
#include <span>
#include <vector>

namespace terratin::detail {

/// The cells to keep as vertices along a border, given the elevations of its cells in
/// increasing column (or row) order, as both tiles read them (NaN: no data): the two ends of every
/// run of valid cells, and as few others as the Douglas-Peucker split needs for every valid cell to
/// lie within `maxError` of the line through the kept cells on either side of it (linear in the
/// cell index). Ascending indices. The result depends only on `elevations` and `maxError`; O(n log
/// n) on typical profiles, O(n^2) at worst (a staircase). `maxError` must be finite and not
/// negative.
std::vector<std::uint32_t> keptBorderCells(std::span<const float> elevations, double maxError);

/// The largest distance, in z, of a valid cell from the line between the kept cells on either
/// side of it (0 for kept cells): the bound keptBorderCells guarantees, measured
/// independently of it. `kept` must hold the ends of every valid run.
double borderProfileError(std::span<const float> elevations, std::span<const std::uint32_t> kept);

} // namespace terratin::detail

#pragma once
/// @file
/// The refiner's measure of a cell against a TIN: how far the cell's elevation lies from the
/// TIN's surface at the cell (its triangle's plane there, or on a tile's side the chord between
/// two of the side's vertices), vertically, in the grid's z units. The scans, the checks, the
/// completion of a constrained TIN and the choice of the tiles' side vertices all measure with
/// it, so that they agree to the last bit (span_measure.cpp's four-lane scan computes the same
/// difference and absolute value).

#include <cmath>

namespace terratin::detail {

/// |z - surfaceZ|: `z` a cell's elevation (the grid's float, exactly as a double), `surfaceZ`
/// the TIN's elevation at the cell's position, as the caller interpolates it.
[[nodiscard]] inline double cellError(double z, double surfaceZ) {
    return std::fabs(z - surfaceZ);
}

} // namespace terratin::detail

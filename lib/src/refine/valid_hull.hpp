#pragma once
/// @file
/// The convex hull of a grid's valid cell centres, the refiner's starting TIN.

#include "terratin/refine/height_grid.hpp"

#include <cstdint>
#include <vector>

namespace terratin::detail {

/// Cells whose centres are the corners of the convex hull of the valid cells' centres in CRS
/// coordinates (HeightGrid::cellCentre), counter-clockwise, without collinear points.
/// Only each row's first and last valid cell can be a corner (every other cell of the row
/// lies between them), so the hull is built from at most 2 * height candidates by Andrew's
/// monotone chain with exact orientation tests. Throws InvalidInputError when there is no
/// valid cell or all valid centres are collinear. O(cells) to find the candidates.
std::vector<std::uint32_t> validHullCells(const HeightGrid& grid);

} // namespace terratin::detail

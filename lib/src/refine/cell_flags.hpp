#pragma once
/// @file
/// The refiner's per-cell flags (grid_scan.hpp's CellFlag): nodata, and which nodata cells
/// form holes that must stay open.

#include "terratin/geometry/height_grid.hpp"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace terratin::detail {

/// One byte per cell, on huge pages like the elevations (see HeightGrid::z).
using CellFlags = std::vector<std::uint8_t, HugePageAllocator<std::uint8_t>>;

/// One byte per cell: kCellNoData for cells without data and, unless `fillHoles`,
/// kCellOpenHole as well for the cells of every 8-connected nodata region of more than
/// `maxHole` cells. Sets `openHoleCells` to the number of such cells.
/// 8-connectivity: nodata cells touching by a corner are one hole, as a person sees a void;
/// a diagonal line of nodata cells is one hole, not a row of single-cell gaps to fill.
/// O(cells) time; a stack of at most one hole's cells.
CellFlags makeCellFlags(const HeightGrid& grid, std::size_t maxHole, bool fillHoles,
                        std::size_t& openHoleCells);

} // namespace terratin::detail

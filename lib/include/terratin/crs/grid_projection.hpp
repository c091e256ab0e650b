#pragma once
/// @file
/// A raster's cell centres in another CRS: the positions refine(grid, positions, ...) takes
/// when a DEM is simplified in a CRS other than its own (a geographic DEM in its UTM zone).

#include "terratin/geometry/height_grid.hpp"
#include "terratin/geometry/point.hpp"

#include <string>
#include <vector>

namespace terratin::crs {

/// Every cell centre of `grid` (HeightGrid::cellCentre, in `sourceWkt`) transformed to
/// `targetWkt` with PROJ, x and y only, row-major, nodata cells included. Parallel over
/// rows (one PROJ transformation per thread). Throws CrsError as Reprojector does (an
/// unreadable CRS, no transformation, a cell outside the target's domain).
/// Memory: 16 bytes per cell.
std::vector<Point2> projectCellCentres(const HeightGrid& grid, const std::string& sourceWkt,
                                       const std::string& targetWkt);

} // namespace terratin::crs

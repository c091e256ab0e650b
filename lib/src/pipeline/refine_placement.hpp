#pragma once
/// @file
/// The CRS a simplified TIN is built in, and where each raster cell lies in it. Internal to
/// the build pipeline.
///
/// The CRS decision is gatherInputs' (gather_inputs.cpp) for one raster: the raster's CRS or
/// --s_srs is the source; the target is --t_srs, else the source, except that a geographic
/// source becomes the UTM/UPS zone of the raster's centre unless --keep-geographic. When the
/// target differs from the source, every cell centre is reprojected and the refiner works
/// with those positions (refine(grid, positions, ...)).

#include "terratin/geometry/height_grid.hpp"
#include "terratin/geometry/point.hpp"
#include "terratin/pipeline/build_pipeline.hpp"

#include <string>
#include <vector>

namespace terratin::detail {

struct RefinePlacement {
    /// The TIN's CRS (WKT2), empty when the raster has none and none was asked for.
    std::string targetWkt;
    /// The position of every cell in targetWkt, row-major; empty when the target is the
    /// raster's own CRS (the refiner then uses the geotransform's cell centres).
    std::vector<Point2> positions;
};

/// The CRS a simplified TIN comes from and the one it is built in.
struct RefineCrs {
    std::string source;
    std::string target;
    /// Whether the cells must be reprojected from source to target.
    [[nodiscard]] bool movesCells() const;
};

/// placeRefinedCells' decision of the target CRS, for a raster whose extent is centred on
/// `centre`, without moving any cell. Fills the report's source CRS fields, zone and notices.
RefineCrs chooseRefineCrs(const BuildOptions& options, Point2 centre, const std::string& rasterWkt,
                          BuildReport& report);

/// Decides the target CRS and reprojects the cell centres (x, y only, in parallel) when it is
/// not the source. Fills the report's source and target CRS fields, zone, reprojected,
/// notices and timings.reproject. Throws CrsError (an unreadable CRS, a raster without CRS
/// asked to be reprojected, a cell PROJ cannot transform).
RefinePlacement placeRefinedCells(const BuildOptions& options, const HeightGrid& grid,
                                  const std::string& rasterWkt, BuildReport& report);

} // namespace terratin::detail

#pragma once
/// @file
/// GdalRasterReader: DEM rasters (anything GDAL opens) to planar points at cell centres.

#include "terratin/geometry/point.hpp"
#include "terratin/progress.hpp"

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace terratin::io {

/// GDAL's affine geotransform: x = c[0] + col*c[1] + row*c[2], y = c[3] + col*c[4] + row*c[5],
/// with (col, row) in pixel units from the raster's top-left corner.
struct GeoTransform {
    std::array<double, 6> c{0.0, 1.0, 0.0, 0.0, 0.0, 1.0};

    /// Georeferenced centre of cell (row, col): the transform at (col + 0.5, row + 0.5).
    [[nodiscard]] Point2 cellCentre(std::int64_t row, std::int64_t col) const;
};

/// What to read from a raster.
struct RasterReadOptions {
    /// 1-based band number.
    int band = 1;
};

/// The valid cells of one raster band as points.
struct RasterPoints {
    /// Cell centres (CRS units) with z = raw value * scale + offset, in row-major order.
    std::vector<Point3> points;
    /// row * width + col of each point.
    std::vector<std::uint64_t> cellIndex;
    /// The raster's CRS as WKT, empty when it has none.
    std::string crsWkt;
    int width = 0;
    int height = 0;
    GeoTransform geoTransform;
    /// Cells skipped because they are nodata, masked out or NaN.
    std::uint64_t skippedCells = 0;
};

/// Reads every valid cell of `options.band` of the raster at `path`, block by block.
/// A cell is skipped when the band's mask (nodata value, mask band, alpha band) excludes it or
/// its value is NaN. Throws IoError when the file cannot be opened as a raster and
/// InvalidInputError when the band does not exist or no cell is valid; throws Cancelled when
/// `progress` returns false.
RasterPoints readRasterPoints(const std::string& path, const RasterReadOptions& options,
                              const ProgressCallback& progress = {});

} // namespace terratin::io

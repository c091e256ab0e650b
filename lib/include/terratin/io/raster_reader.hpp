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
/// with (col, row) in pixel units from the corner of the raster's first stored row and column.
/// c[2] and c[4] are the rotation (shear) terms. c[5] < 0 for the usual north-up raster;
/// c[5] > 0 when rows are stored bottom-up (row 0 is then the southernmost). The default,
/// (0, 1, 0, 0, 0, 1), is GDAL's own for a raster without georeferencing: x, y in pixels.
struct GeoTransform {
    std::array<double, 6> c{0.0, 1.0, 0.0, 0.0, 0.0, 1.0};

    /// Georeferenced centre of cell (row, col), in CRS units: the transform at
    /// (px, py) = (col + 0.5, row + 0.5), evaluated exactly as (c[0] + px*c[1]) + py*c[2] and
    /// (c[3] + px*c[4]) + py*c[5]. readRasterPoints gives bit-identical coordinates.
    [[nodiscard]] Point2 cellCentre(std::int64_t row, std::int64_t col) const;
};

/// What to read from a raster.
struct RasterReadOptions {
    /// 1-based band number.
    int band = 1;
};

/// The valid cells of one raster band as points.
struct RasterPoints {
    /// Cell centres (CRS units, GeoTransform::cellCentre) in row-major storage order, with
    /// z = raw * scale + offset (band units) when the band declares a scale or an offset, and
    /// z = raw exactly (read as Float64) when it declares neither.
    std::vector<Point3> points;
    /// row * width + col of each point; strictly increasing.
    std::vector<std::uint64_t> cellIndex;
    /// The raster's CRS as WKT2:2019 (WKT1 when GDAL cannot export WKT2), empty when it has none.
    /// Coordinates are in GDAL's traditional GIS order (x = easting / longitude) whatever the
    /// axis order the WKT declares (EPSG:4326 declares latitude first): import it with
    /// OAMS_TRADITIONAL_GIS_ORDER.
    std::string crsWkt;
    /// Raster size in cells.
    int width = 0;
    int height = 0;
    /// The raster's geotransform, or GDAL's default (0, 1, 0, 0, 0, 1) when it has none.
    GeoTransform geoTransform;
    /// Cells skipped because they are nodata, masked out or NaN;
    /// points.size() + skippedCells == width * height.
    std::uint64_t skippedCells = 0;
};

/// Reads every valid cell of `options.band` of the raster at `path` (anything GDAL opens as a
/// raster, including /vsi paths), one strip of whole block rows at a time.
/// A cell is skipped when the band's GDAL mask excludes it (nodata value compared in the band's
/// own data type, per-dataset mask, alpha band) or its value is NaN.
/// `progress` is called after each strip with the fraction of rows read.
/// Throws IoError ("GdalRasterReader: cannot open raster '<path>': <GDAL message>") when the
/// file is missing or is not a raster, or a read fails; InvalidInputError when the band is not in
/// 1..band count, or no cell is valid ("no valid cells"), or the raster cannot fit in memory as
/// points; Cancelled when `progress` returns false.
/// Complexity: O(width * height) time; memory 32 bytes per cell for the result (reserved up
/// front, released down to the valid cells when over a quarter were skipped) plus 9 bytes per
/// cell of one strip.
RasterPoints readRasterPoints(const std::string& path, const RasterReadOptions& options,
                              const ProgressCallback& progress = {});

} // namespace terratin::io

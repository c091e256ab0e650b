#pragma once
/// @file
/// PointCloud: what every input reader (raster, LAS, delimited text, OGR points) hands to the
/// pipeline. One struct for all sources, so that merging, reprojection and reporting need not
/// know where the points came from.

#include "terratin/geometry/point.hpp"

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace terratin::io {

/// The kind of file an input is, as input_reader.hpp decides it.
enum class InputKind {
    Raster, ///< any raster GDAL opens (GeoTIFF, HGT, DTED, ASCII grid...)
    Las,    ///< ASPRS LAS 1.0-1.4, uncompressed
    Laz,    ///< LAS compressed by LASzip (COPC too); detected as Las, read by the same reader
    Text,   ///< delimited text, one point per line
    Vector, ///< an OGR vector dataset with point features
};

/// "raster", "las", "laz", "text" or "vector".
const char* toString(InputKind kind);

/// Points read from one input, in the input's own CRS and units.
struct PointCloud {
    /// The path the points were read from.
    std::string path;
    InputKind kind = InputKind::Raster;
    /// x, y in the units of `crsWkt` (traditional GIS order: x = easting / longitude), z in the
    /// source's vertical units, exactly as the file stores them after its own scale and offset.
    std::vector<Point3> points;
    /// Rasters only: row * width + col of each point (strictly increasing); empty otherwise.
    std::vector<std::uint64_t> cellIndex;
    /// Rasters only: the width and height in cells and the geotransform that placed the
    /// points (io::GeoTransform::cellCentre); 0 otherwise.
    std::uint64_t rasterWidth = 0;
    std::uint64_t rasterHeight = 0;
    std::array<double, 6> rasterGeoTransform{0.0, 1.0, 0.0, 0.0, 0.0, 1.0};
    /// The input's CRS as WKT, empty when the file declares none.
    std::string crsWkt;
    /// Records the file holds: LAS point records, text data lines, OGR features, raster cells.
    std::uint64_t recordsRead = 0;
    /// Records dropped on purpose: LAS class / return filter and withheld points, OGR features
    /// without a point geometry or with a null z field.
    std::uint64_t filteredOut = 0;
    /// Rasters only: nodata, masked or NaN cells skipped.
    std::uint64_t skippedCells = 0;
};

} // namespace terratin::io

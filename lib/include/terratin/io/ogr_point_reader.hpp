#pragma once
/// @file
/// OgrPointReader: the point features of any OGR vector dataset (GeoPackage, Shapefile,
/// GeoJSON, FlatGeobuf, CSV with geometry...) to points.

#include "terratin/io/point_source.hpp"
#include "terratin/progress.hpp"

#include <string>

namespace terratin::io {

/// What to read from a vector dataset.
struct OgrPointReadOptions {
    /// Layer to read; empty: the first layer holding point features.
    std::string layer;
    /// Numeric attribute holding the elevation; empty: z of the (3D) point geometry.
    std::string zField;
};

/// Reads every Point and every point of a MultiPoint of the chosen layer, in feature order,
/// with x, y from the geometry (traditional GIS order: x = easting / longitude) and z from the
/// geometry or from `options.zField`. Features without a point geometry (null, empty, lines,
/// polygons) and features whose z field is null are dropped and counted in filteredOut.
/// PointCloud::crsWkt is the layer's CRS (empty when it has none).
/// Throws IoError when the dataset cannot be opened as vector data; InvalidInputError for a
/// missing layer or z field, a non-numeric z field, 2D points without `zField`, or a layer
/// without any point; Cancelled when `progress` returns false.
/// Complexity: O(features).
PointCloud readOgrPoints(const std::string& path, const OgrPointReadOptions& options = {},
                         const ProgressCallback& progress = {});

} // namespace terratin::io

#pragma once
/// @file
/// OgrLineReader: the line and polygon features of an OGR vector dataset (breaklines, clip and
/// erase areas) as polylines.

#include "terratin/geometry/point.hpp"

#include <cstdint>
#include <string>
#include <vector>

namespace terratin::io {

/// The lines of one layer, in feature order.
struct LineLayer {
    /// Where they came from: "FILE" or "FILE|layername=NAME" as given, and the layer read.
    std::string source;
    std::string layerName;
    /// One polyline per LineString (a MultiLineString gives one per part), in the layer's CRS.
    /// z is the geometry's, NaN for a 2D line.
    std::vector<std::vector<Point3>> lines;
    /// The FID of the feature each line came from, for messages.
    std::vector<std::int64_t> featureIds;
    /// Whether any line has z.
    bool hasZ = false;
    /// Polygon layers (readOgrPolygons): each line is a closed ring (last point = first), and
    /// polygonOf[i] numbers the polygon ring i belongs to (its first ring is the exterior, the
    /// others holes). Empty for line layers.
    std::vector<std::size_t> polygonOf;
    /// readOgrPolygons with a value field: polygonValues[k] is polygon k's value of that field.
    /// Empty otherwise.
    std::vector<double> polygonValues;
    /// The layer's CRS as WKT, empty when it has none.
    std::string crsWkt;
};

/// Reads every LineString and MultiLineString (2D or 3D) of a layer. `source` is a file name,
/// optionally followed by "|layername=NAME"; `layer` (when not empty) names the layer instead;
/// with neither, the dataset must hold exactly one layer. Null and empty geometries are
/// skipped. `option` names the option the source came from, for messages ("--breaklines").
/// Throws IoError when the dataset cannot be opened, InvalidInputError for a missing or
/// ambiguous layer, a feature whose geometry is not a line (naming its FID), or a non-finite
/// coordinate. Complexity: O(vertices).
LineLayer readOgrLines(const std::string& source, const std::string& layer,
                       const std::string& option);

/// The rings of every Polygon and MultiPolygon of a layer (clip, erase and replace areas), as
/// readOgrLines reads lines. With a `valueField`, each polygon's value of that numeric
/// attribute goes into polygonValues (every part of a MultiPolygon gets its feature's value).
/// Throws InvalidInputError for a feature that is not a polygon, or is not a valid one (a
/// self-intersecting ring, say), or has no finite value in `valueField`, naming its FID; and for
/// a `valueField` the layer lacks or that is not numeric, naming the layer's fields.
LineLayer readOgrPolygons(const std::string& source, const std::string& layer,
                          const std::string& option, const std::string& valueField = {});

} // namespace terratin::io

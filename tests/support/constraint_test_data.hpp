#pragma once
// Test data for the constraint options (breaklines, clip, erase, replace): vector layers, the
// bundled sample's cells, scattered points of a plane; and an even-odd point-in-polygon test
// written apart from the library's.

#include "terratin/geometry/point.hpp"

#include <filesystem>
#include <limits>
#include <string>
#include <vector>

namespace terratin::test {

/// ridges_utm.tif: 320 x 240 cells of 10 m, EPSG:32633, cell centres 455005..458195 x
/// 5102605..5104995.
inline constexpr int kSampleColumns = 320;
inline constexpr int kSampleRows = 240;
Point2 sampleCellCentre(int column, int row);
/// A pentagonal lake inside the sample's data, its corners off the cell grid (no closing point).
std::vector<Point2> sampleLake();

/// A GeoPackage at `path` with layer `layer` in EPSG:`epsg` (0: no CRS) holding one feature
/// per WKT. With `levelType` (an OGRFieldType: 0 = OFTInteger, 2 = OFTReal, 4 = OFTString),
/// the layer has a field "level", set to `levels[i]` on feature i where given and not NaN.
/// Fails the test (ADD_FAILURE) when GDAL refuses anything.
void writeVectorLayer(const std::filesystem::path& path, const std::string& layer,
                      const std::vector<std::string>& wkts, int epsg = 32633,
                      const std::vector<double>& levels = {}, int levelType = -1);

/// "POLYGON ((...))" of a ring given without its closing point; "LINESTRING (...)" of points.
std::string polygonWkt(const std::vector<Point2>& ring);
std::string lineWkt(const std::vector<Point2>& points);

/// Whether `p` lies inside `ring` (even-odd; a point on the ring may count either way).
bool insideRing(const std::vector<Point2>& ring, Point2 p);

/// Band 1 of a raster as floats, row by row; NaN where it has no data.
std::vector<float> readElevations(const std::filesystem::path& raster);

/// A Float32 GeoTIFF at `path`, `width` x `height` cells of `cellSize` m from the top left
/// corner (x0, y0), in EPSG:32633, holding `z` row by row, NaN written as the no-data value
/// -9999. Fails the test (ADD_FAILURE) when GDAL refuses anything.
void writeElevations(const std::filesystem::path& path, int width, int height, double x0, double y0,
                     double cellSize, std::vector<float> z);

/// The centres of the valid cells of band 1 of `raster` (not its no-data value, not NaN), in
/// its CRS, from its geotransform (north up).
std::vector<Point2> validCellCentres(const std::filesystem::path& raster);

/// Computed by GEOS (through OGR), apart from the library: the area of the convex hull of
/// `points` and that of its intersection with the polygon `ring` (given without its closing
/// point), in the square of the points' unit. Fails the test (ADD_FAILURE) without GEOS.
struct HullOverlap {
    double hull = 0.0;
    double overlap = 0.0;
};
HullOverlap hullOverlap(const std::vector<Point2>& points, const std::vector<Point2>& ring);

/// `count` scattered points (a fixed generator) in [0, 1000)^2 on the plane
/// z = x / 100 + y / 50, written as "x y z" lines to `path`; returns their x, y.
std::vector<Point2> writePlanePoints(const std::filesystem::path& path, int count,
                                     std::uint64_t seed);

} // namespace terratin::test

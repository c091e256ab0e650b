#pragma once
/// @file
/// A DEM held once in memory for terrain simplification: one float32 elevation per cell,
/// NaN for a cell without data, and the affine geotransform that places cell centres.

#include "terratin/detail/huge_page_allocator.hpp"
#include "terratin/geometry/point.hpp"

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace terratin {

/// The elevations of a HeightGrid: a std::vector in every use, whose memory lies on 2 MiB pages
/// once it is a megabyte or more (the refiner reads a triangle's rows at a time, all over the
/// raster). Its allocator is the library's (terratin::detail): name the type HeightArray.
using HeightArray = std::vector<float, detail::HugePageAllocator<float>>;

/// A raster band as a regular grid of elevations.
///
/// Cells are numbered row-major from the first stored row and column: cell = row * width + col.
/// `z[cell]` is the elevation in the band's vertical units, or NaN when the cell has no data
/// (nodata, masked out or NaN in the source): NaN is the validity mask, so the grid costs 4
/// bytes per cell. Elevations are float32: exact for Int16, UInt16, Byte and Float32 bands and
/// for integers up to 2^24; a Float64 or scaled band is rounded to the nearest float32 (well
/// under a millimetre for terrain), and the TIN's vertices carry exactly that value.
struct HeightGrid {
    int width = 0;
    int height = 0;
    /// GDAL's affine geotransform: x = c[0] + col*c[1] + row*c[2], y = c[3] + col*c[4] +
    /// row*c[5], (col, row) in pixels from the raster's corner (the first stored cell's, unless
    /// the grid is a window: firstRow). CRS units.
    std::array<double, 6> geoTransform{0.0, 1.0, 0.0, 0.0, 0.0, 1.0};
    /// width * height elevations, row-major; NaN = no data.
    HeightArray z;
    /// Where this grid's first cell lies in the raster the geotransform describes: 0, 0 for a
    /// whole raster; a tile's first row and column for a window of it (a tiled read), so that a
    /// cell has bit for bit the centre it has in the whole raster, whichever tile holds it.
    int firstRow = 0;
    int firstColumn = 0;

    /// Georeferenced centre of cell (row, col): the transform at (px, py) = (firstColumn + col +
    /// 0.5, firstRow + row + 0.5), evaluated as (c[0] + px*c[1]) + py*c[2] and (c[3] + px*c[4]) +
    /// py*c[5], bit-identical to io::GeoTransform::cellCentre and to the points of
    /// io::readRasterPoints.
    [[nodiscard]] Point2 cellCentre(std::int64_t row, std::int64_t col) const {
        const double px = static_cast<double>(col + firstColumn) + 0.5;
        const double py = static_cast<double>(row + firstRow) + 0.5;
        const std::array<double, 6>& c = geoTransform;
        return {c[0] + px * c[1] + py * c[2], c[3] + px * c[4] + py * c[5]};
    }
    [[nodiscard]] Point2 cellCentre(std::uint64_t cell) const {
        const auto w = static_cast<std::uint64_t>(width);
        return cellCentre(static_cast<std::int64_t>(cell / w), static_cast<std::int64_t>(cell % w));
    }
    /// Georeferenced centre of the raster's extent (pixel (width / 2, height / 2)).
    [[nodiscard]] Point2 extentCentre() const {
        const double px = static_cast<double>(firstColumn) + 0.5 * static_cast<double>(width);
        const double py = static_cast<double>(firstRow) + 0.5 * static_cast<double>(height);
        const std::array<double, 6>& c = geoTransform;
        return {c[0] + px * c[1] + py * c[2], c[3] + px * c[4] + py * c[5]};
    }
    [[nodiscard]] std::size_t cellCount() const {
        return static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
    }
    [[nodiscard]] bool isValid(std::size_t cell) const { return !std::isnan(z[cell]); }
    /// Cells with data. O(width * height).
    [[nodiscard]] std::size_t validCount() const;
    /// Stores `elevations` (z units, NaN = no data) into the cells from `firstCell` on, each
    /// rounded to the nearest float32: the one rounding a DEM's values go through on their way
    /// into a grid, whoever reads them (the raster reader, the Python module).
    /// Precondition: firstCell + elevations.size() <= cellCount().
    void storeElevations(std::size_t firstCell, std::span<const double> elevations);
};

/// The bilinear interpolation of `grid`'s elevations at `p` (CRS units): the four cells whose
/// centres surround p, weighted by p's fractional column and row (the geotransform inverted;
/// rotated grids too). NaN unless all four have data and p lies inside or on the quadrilateral
/// of their centres, decided exactly (orient2d): a point given an elevation lies inside the
/// convex hull of the valid cells' centres.
double bilinearElevation(const HeightGrid& grid, Point2 p);

/// Largest magnitude of a cell-centre coordinate accepted from a geotransform, in CRS units.
/// No terrestrial CRS comes near it (the largest, in US survey feet, span about 1.3e8), and above
/// 2^53 ≈ 9e15 a double no longer holds whole units: a geotransform that reaches further is
/// corrupt, and would leave the triangulator with coincident or overflowing points.
inline constexpr double kMaxGeoCoordinate = 1e15;

/// Why the geotransform `c` of a width x height raster is unusable; empty when it is usable:
/// every coefficient finite, cells of non-zero area, every cell centre within
/// kMaxGeoCoordinate (the four corner cells bound them all, the transform being affine).
std::string geoTransformProblem(const std::array<double, 6>& c, std::int64_t width,
                                std::int64_t height);

/// "(c0, c1, c2, c3, c4, c5)", each coefficient in its shortest exact form, for messages.
std::string geoTransformText(const std::array<double, 6>& c);

} // namespace terratin

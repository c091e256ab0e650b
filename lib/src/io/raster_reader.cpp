/// @file
/// GdalRasterReader: one raster band to cell-centre points, read one strip of rows at a time
/// (validity and elevation rules in raster_band_reader.hpp).
///
/// Notation: (row, col) are 0-based cell indices from the raster's first stored row and column;
/// c[0..5] is GDAL's affine geotransform (GDAL Raster Data Model, "Affine GeoTransform").

#include "terratin/io/raster_reader.hpp"

#include "raster_band_reader.hpp"

#include "terratin/error.hpp"

#include <cmath>
#include <new>
#include <stdexcept>
#include <string_view>

namespace terratin::io {

namespace {

constexpr std::string_view kStage = "GdalRasterReader";

/// The affine transform at fractional pixel position (col + 0.5, row + 0.5), evaluated in one
/// fixed order so that cellCentre() and the read loop give bit-identical coordinates.
inline Point2 affineCellCentre(const std::array<double, 6>& c, double row, double col) {
    const double px = col + 0.5;
    const double py = row + 0.5;
    return {c[0] + px * c[1] + py * c[2], c[3] + px * c[4] + py * c[5]};
}

/// Room in `result` for a point per cell of `reader`'s band; InvalidInputError when memory
/// cannot hold them.
void reserveCells(RasterPoints& result, const detail::RasterBandReader& reader) {
    const auto tooLarge = [&] {
        return InvalidInputError(std::string(kStage) + ": " + reader.quotedPath() + " has " +
                                 std::to_string(reader.width()) + " x " +
                                 std::to_string(reader.height()) +
                                 " cells: out of memory holding them as points (32 bytes a cell)");
    };
    try {
        result.points.reserve(reader.cellCount());
        result.cellIndex.reserve(reader.cellCount());
    } catch (const std::bad_alloc&) {
        throw tooLarge();
    } catch (const std::length_error&) {
        throw tooLarge();
    }
}

} // namespace

Point2 GeoTransform::cellCentre(std::int64_t row, std::int64_t col) const {
    return affineCellCentre(c, static_cast<double>(row), static_cast<double>(col));
}

RasterPoints readRasterPoints(const std::string& path, const RasterReadOptions& options,
                              const ProgressCallback& progress) {
    detail::RasterBandReader reader(path, options.band, kStage);
    RasterPoints result;
    result.width = static_cast<int>(reader.width());
    result.height = static_cast<int>(reader.height());
    result.geoTransform.c = reader.geoTransform();
    result.crsWkt = reader.crsWkt();
    const std::int64_t width = reader.width();
    const std::array<double, 6>& c = result.geoTransform.c;

    // The result is at most one point per cell: reserving that avoids every reallocation, and
    // the excess (nodata frames) is released at the end when it is large.
    const std::uint64_t cellCount = reader.cellCount();
    reserveCells(result, reader);

    // Keep valid cells in row-major order.
    const std::uint64_t valid = reader.readStrips(
        [&](std::int64_t firstRow, std::span<const double> z) {
            const auto rows = static_cast<std::int64_t>(z.size()) / width;
            for (std::int64_t r = 0; r < rows; ++r) {
                const std::int64_t row = firstRow + r;
                const double* rowZ = z.data() + r * width;
                for (std::int64_t col = 0; col < width; ++col) {
                    if (std::isnan(rowZ[col]))
                        continue;
                    const Point2 centre =
                        affineCellCentre(c, static_cast<double>(row), static_cast<double>(col));
                    result.points.push_back({centre.x, centre.y, rowZ[col]});
                    result.cellIndex.push_back(static_cast<std::uint64_t>(row * width + col));
                }
            }
        },
        progress);
    result.skippedCells = cellCount - valid;

    if (result.points.empty())
        throw InvalidInputError(std::string(kStage) + ": no valid cells in band " +
                                std::to_string(options.band) + " of " + reader.quotedPath() +
                                ": all " + std::to_string(cellCount) +
                                " cells are nodata, masked out or NaN");

    // Give back the reservation for skipped cells when it is a sizeable share (over a quarter).
    if (result.skippedCells > cellCount / 4) {
        result.points.shrink_to_fit();
        result.cellIndex.shrink_to_fit();
    }
    return result;
}

} // namespace terratin::io

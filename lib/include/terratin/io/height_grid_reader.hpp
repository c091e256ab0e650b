#pragma once
/// @file
/// GdalHeightGridReader: one raster band as a HeightGrid (float32 per cell, NaN = no data),
/// the compact form terrain refinement works on: 4 bytes per cell instead of the 32 of
/// readRasterPoints.

#include "terratin/geometry/height_grid.hpp"
#include "terratin/io/raster_reader.hpp"
#include "terratin/progress.hpp"
#include "terratin/tile/cell_source.hpp"

#include <array>
#include <cstdint>
#include <memory>
#include <string>

namespace terratin::io {

/// A raster band as a grid, with what the pipeline reports.
struct HeightGridRaster {
    HeightGrid grid;
    /// As RasterPoints::crsWkt (WKT2:2019, GIS axis order), empty when the raster has none.
    std::string crsWkt;
    /// Cells without data (nodata, masked out, NaN).
    std::uint64_t skippedCells = 0;
};

/// Reads band `options.band` of the raster at `path`. Validity is decided as by
/// readRasterPoints (GDAL's mask band, NaN); z = raw * scale + offset when the band declares
/// either, rounded to float32 (exact for integer bands up to 2^24 and Float32 bands). The
/// geotransform is the raster's (GDAL's default without one), so grid.cellCentre gives the
/// same centres as readRasterPoints. Throws IoError, InvalidInputError (band out of range,
/// no valid cell, more than kMaxRefineCells cells, too large for memory), Cancelled, with the
/// stage "GdalHeightGridReader".
/// O(cells) time; 4 bytes per cell plus one strip of 9 bytes per cell.
HeightGridRaster readHeightGrid(const std::string& path, const RasterReadOptions& options,
                                const ProgressCallback& progress = {});

namespace detail {
class RasterBandReader;
}

/// Band `options.band` of the raster at `path`, read a window at a time (a tile's cells):
/// only the cells asked for are held. Validity and elevations as readHeightGrid's, so a window
/// holds bit for bit the cells readHeightGrid would. Opening throws as readHeightGrid does;
/// window() throws IoError when GDAL cannot read the cells, InvalidInputError for an infinite
/// elevation. GDAL's block cache is emptied after each window.
class RasterCells final : public CellSource {
public:
    RasterCells(const std::string& path, const RasterReadOptions& options);
    ~RasterCells() override;
    RasterCells(const RasterCells&) = delete;
    RasterCells& operator=(const RasterCells&) = delete;

    [[nodiscard]] int width() const override;
    [[nodiscard]] int height() const override;
    [[nodiscard]] std::array<double, 6> geoTransform() const override;
    /// As HeightGridRaster::crsWkt.
    [[nodiscard]] const std::string& crsWkt() const;
    [[nodiscard]] HeightGrid window(int firstRow, int rows, int firstColumn, int columns) override;

private:
    std::unique_ptr<detail::RasterBandReader> m_reader;
};

} // namespace terratin::io

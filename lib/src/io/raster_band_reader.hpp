#pragma once
/// @file
/// One raster band read in strips of whole rows, with terratin's validity and elevation rules;
/// shared by readRasterPoints (points per valid cell) and readHeightGrid (a float32 grid).
///
/// Validity of a cell is decided by GDAL's mask band (RFC 15), which already implements the
/// nodata comparison in the band's own data type (a Float32 nodata of -3.4e38 is compared as the
/// float it was stored as, not as the double in the metadata), per-dataset masks and alpha
/// bands. A NaN value is invalid as well, whatever the mask says. z = raw * scale + offset only
/// when the band declares either; otherwise z is raw exactly.

#include "terratin/progress.hpp"

#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace terratin::io::detail {

class RasterBandReader {
public:
    /// Opens band `band` (1-based) of the raster at `path`. Errors name `stage`: IoError when
    /// GDAL cannot open or read it, InvalidInputError for a missing band.
    RasterBandReader(const std::string& path, int band, std::string_view stage);
    ~RasterBandReader();
    RasterBandReader(const RasterBandReader&) = delete;
    RasterBandReader& operator=(const RasterBandReader&) = delete;

    [[nodiscard]] std::int64_t width() const { return m_width; }
    [[nodiscard]] std::int64_t height() const { return m_height; }
    [[nodiscard]] std::uint64_t cellCount() const {
        return static_cast<std::uint64_t>(m_width) * static_cast<std::uint64_t>(m_height);
    }
    /// GDAL's affine geotransform; (0, 1, 0, 0, 0, 1) when the raster has none, so that cell
    /// (row, col) has centre (col + 0.5, row + 0.5) in pixel units.
    [[nodiscard]] const std::array<double, 6>& geoTransform() const { return m_geoTransform; }
    /// The CRS as WKT2:2019 (WKT1 for one that WKT2 export rejects); empty when none.
    [[nodiscard]] const std::string& crsWkt() const { return m_crsWkt; }

    /// Receives rows [firstRow, firstRow + z.size() / width) as elevations, NaN where invalid.
    using StripVisitor = std::function<void(std::int64_t firstRow, std::span<const double> z)>;

    /// Reads the band top to bottom in strips of whole rows (a multiple of the block height,
    /// grown to about 2^18 cells), calling `visit` for each and `progress` after each; throws
    /// Cancelled when `progress` returns false. Returns the number of valid cells.
    std::uint64_t readStrips(const StripVisitor& visit, const ProgressCallback& progress);

    /// A window of cells: rows firstRow .. firstRow + rows - 1, likewise for columns.
    struct CellBox {
        std::int64_t firstRow = 0;
        std::int64_t rows = 0;
        std::int64_t firstColumn = 0;
        std::int64_t columns = 0;
    };

    /// The window's elevations, row-major, NaN where invalid, by the rules of readStrips.
    /// Throws IoError when GDAL cannot read it, std::out_of_range for a window outside the
    /// raster.
    std::vector<double> readWindow(const CellBox& box);

    /// "'path'", for messages.
    [[nodiscard]] std::string quotedPath() const { return "'" + m_path + "'"; }

private:
    /// How the band's raw values become elevations.
    struct BandRules {
        bool allValid = true;
        void* mask = nullptr; // GDALRasterBandH, without gdal.h here
        bool applyScaleOffset = false;
        double scale = 1.0;
        double offset = 0.0;
    };
    [[nodiscard]] BandRules bandRules() const;
    /// Reads `box` into values (and mask) and turns them into elevations; returns the valid.
    std::uint64_t readCells(const BandRules& rules, const CellBox& box, std::vector<double>& values,
                            std::vector<std::uint8_t>& mask) const;

    struct Dataset;
    std::unique_ptr<Dataset> m_dataset;
    std::string m_path;
    std::string m_stage;
    int m_band = 1;
    std::int64_t m_width = 0;
    std::int64_t m_height = 0;
    std::array<double, 6> m_geoTransform{0.0, 1.0, 0.0, 0.0, 0.0, 1.0};
    std::string m_crsWkt;
};

} // namespace terratin::io::detail

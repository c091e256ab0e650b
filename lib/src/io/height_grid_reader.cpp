/// @file
/// GdalHeightGridReader: a band read in strips of whole rows straight into float32 cells, with
/// the same validity rules as GdalRasterReader (raster_band_reader.hpp).

#include "terratin/io/height_grid_reader.hpp"

#include "raster_band_reader.hpp"

#include "terratin/error.hpp"
#include "terratin/refine/refine.hpp"

#include <algorithm>
#include <cmath>
#include <new>
#include <string_view>

namespace terratin::io {

namespace {
constexpr std::string_view kStage = "GdalHeightGridReader";
} // namespace

HeightGridRaster readHeightGrid(const std::string& path, const RasterReadOptions& options,
                                const ProgressCallback& progress) {
    detail::RasterBandReader reader(path, options.band, kStage);
    HeightGridRaster result;
    HeightGrid& grid = result.grid;
    grid.width = static_cast<int>(reader.width());
    grid.height = static_cast<int>(reader.height());
    grid.geoTransform = reader.geoTransform();
    result.crsWkt = reader.crsWkt();
    // Before any allocation: a raster that declares more cells than a grid can number (a VRT
    // of 10^6 x 10^6, say) is refused at once, never zero-filled for hours toward the OOM
    // killer where the kernel lets any allocation through.
    if (reader.cellCount() > kMaxRefineCells)
        throw InvalidInputError(std::string(kStage) + ": " + reader.quotedPath() + " has " +
                                std::to_string(reader.width()) + " x " +
                                std::to_string(reader.height()) + " cells, more than one grid " +
                                "holds (" + std::to_string(kMaxRefineCells) +
                                "); simplify it in tiles");
    try {
        grid.z.resize(grid.cellCount());
    } catch (const std::bad_alloc&) {
        throw InvalidInputError(std::string(kStage) + ": " + reader.quotedPath() + " has " +
                                std::to_string(grid.width) + " x " + std::to_string(grid.height) +
                                " cells: out of memory holding them (4 bytes a cell)");
    }

    const std::uint64_t valid = reader.readStrips(
        [&](std::int64_t firstRow, std::span<const double> z) {
            grid.storeElevations(static_cast<std::size_t>(firstRow * reader.width()), z);
        },
        progress);
    const std::uint64_t cellCount = reader.cellCount();
    if (valid == 0)
        throw InvalidInputError(std::string(kStage) + ": no valid cells in band " +
                                std::to_string(options.band) + " of " + reader.quotedPath() +
                                ": all " + std::to_string(cellCount) +
                                " cells are nodata, masked out or NaN");
    result.skippedCells = cellCount - valid;
    return result;
}

RasterCells::RasterCells(const std::string& path, const RasterReadOptions& options)
    : m_reader(std::make_unique<detail::RasterBandReader>(path, options.band, kStage)) {}

RasterCells::~RasterCells() = default;

int RasterCells::width() const {
    return static_cast<int>(m_reader->width());
}

int RasterCells::height() const {
    return static_cast<int>(m_reader->height());
}

std::array<double, 6> RasterCells::geoTransform() const {
    return m_reader->geoTransform();
}

const std::string& RasterCells::crsWkt() const {
    return m_reader->crsWkt();
}

HeightGrid RasterCells::window(int firstRow, int rows, int firstColumn, int columns) {
    HeightGrid window;
    window.width = columns;
    window.height = rows;
    window.geoTransform = m_reader->geoTransform();
    window.firstRow = firstRow;
    window.firstColumn = firstColumn;
    window.z.resize(window.cellCount());
    window.storeElevations(0, m_reader->readWindow({firstRow, rows, firstColumn, columns}));
    const auto infinite =
        std::find_if(window.z.begin(), window.z.end(), [](float z) { return std::isinf(z); });
    if (infinite != window.z.end()) {
        const auto cell = static_cast<int>(infinite - window.z.begin());
        throw InvalidInputError(std::string(kStage) + ": cell (row " +
                                std::to_string(firstRow + cell / columns) + ", column " +
                                std::to_string(firstColumn + cell % columns) + ") of " +
                                m_reader->quotedPath() + " has an infinite elevation");
    }
    return window;
}

} // namespace terratin::io

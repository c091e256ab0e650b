/// @file
/// GdalHeightGridReader: a band read in strips of whole block rows straight into float32 cells,
/// with the same validity rules as GdalRasterReader (raster_reader.cpp).

#include "terratin/io/height_grid_reader.hpp"

#include "terratin/error.hpp"
#include "terratin/io/gdal_error.hpp"

#include <cpl_conv.h>
#include <gdal.h>
#include <ogr_srs_api.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <memory>
#include <new>
#include <string_view>
#include <vector>

namespace terratin::io {

namespace {

constexpr std::string_view kStage = "GdalHeightGridReader";

// Strips of at least this many cells (2 MiB of Float64): few RasterIO calls for rasters stored
// one row per block, and little memory beside the grid.
constexpr std::int64_t kMinStripCells = std::int64_t{1} << 18;

struct DatasetCloser {
    void operator()(void* dataset) const { GDALClose(dataset); }
};

std::string crsAsWkt(GDALDatasetH dataset) {
    OGRSpatialReferenceH srs = GDALGetSpatialRef(dataset);
    if (srs == nullptr)
        return {};
    const char* const wkt2Options[] = {"FORMAT=WKT2_2019", nullptr};
    char* raw = nullptr;
    if (OSRExportToWktEx(srs, &raw, wkt2Options) != OGRERR_NONE || raw == nullptr || *raw == '\0') {
        CPLFree(raw);
        raw = nullptr;
        if (OSRExportToWkt(srs, &raw) != OGRERR_NONE) {
            CPLFree(raw);
            return {};
        }
    }
    std::string wkt = raw != nullptr ? std::string(raw) : std::string();
    CPLFree(raw);
    return wkt;
}

std::string quoted(const std::string& path) { return "'" + path + "'"; }

} // namespace

HeightGridRaster readHeightGrid(const std::string& path, const RasterReadOptions& options,
                                const ProgressCallback& progress) {
    initialiseGdal();
    CPLErrorReset();
    const std::unique_ptr<void, DatasetCloser> dataset(GDALOpenEx(
        path.c_str(), GDAL_OF_RASTER | GDAL_OF_VERBOSE_ERROR, nullptr, nullptr, nullptr));
    if (!dataset)
        throwGdalError(kStage, "cannot open raster", path);
    GDALDatasetH ds = dataset.get();
    const int bandCount = GDALGetRasterCount(ds);
    if (options.band < 1 || options.band > bandCount)
        throw InvalidInputError(std::string(kStage) + ": band " + std::to_string(options.band) +
                                " does not exist in " + quoted(path) + ", which has " +
                                std::to_string(bandCount) + " band(s) numbered from 1");
    GDALRasterBandH band = GDALGetRasterBand(ds, options.band);
    if (band == nullptr)
        throwGdalError(kStage, "cannot access band " + std::to_string(options.band) + " of", path);

    HeightGridRaster result;
    HeightGrid& grid = result.grid;
    grid.width = GDALGetRasterXSize(ds);
    grid.height = GDALGetRasterYSize(ds);
    const std::int64_t width = grid.width;
    const std::int64_t height = grid.height;
    std::array<double, 6> c{0.0, 1.0, 0.0, 0.0, 0.0, 1.0};
    if (GDALGetGeoTransform(ds, c.data()) != CE_None)
        c = {0.0, 1.0, 0.0, 0.0, 0.0, 1.0};
    CPLErrorReset();
    grid.geoTransform = c;
    result.crsWkt = crsAsWkt(ds);

    int hasScale = 0;
    int hasOffset = 0;
    const double scale = GDALGetRasterScale(band, &hasScale);
    const double offset = GDALGetRasterOffset(band, &hasOffset);
    const bool applyScaleOffset = hasScale != 0 || hasOffset != 0;
    const double zScale = hasScale != 0 ? scale : 1.0;
    const double zOffset = hasOffset != 0 ? offset : 0.0;

    const bool allValid = (GDALGetMaskFlags(band) & GMF_ALL_VALID) != 0;
    GDALRasterBandH maskBand = allValid ? nullptr : GDALGetMaskBand(band);
    if (!allValid && maskBand == nullptr)
        throwGdalError(kStage, "cannot get the mask of band " + std::to_string(options.band) + " of",
                       path);

    int blockXSize = 0;
    int blockYSize = 0;
    GDALGetBlockSize(band, &blockXSize, &blockYSize);
    const std::int64_t blockRows =
        std::clamp<std::int64_t>(blockYSize, 1, std::max<std::int64_t>(height, 1));
    const std::int64_t perStrip =
        std::max<std::int64_t>(1, kMinStripCells / std::max<std::int64_t>(width * blockRows, 1));
    const std::int64_t stripRows =
        std::min(std::max<std::int64_t>(height, 1), blockRows * perStrip);

    std::vector<double> values;
    std::vector<std::uint8_t> mask;
    try {
        grid.z.resize(grid.cellCount());
        values.resize(static_cast<std::size_t>(stripRows * width));
        if (!allValid)
            mask.assign(values.size(), 0);
    } catch (const std::bad_alloc&) {
        throw InvalidInputError(std::string(kStage) + ": " + quoted(path) + " has " +
                                std::to_string(width) + " x " + std::to_string(height) +
                                " cells, too many to hold in memory");
    }

    constexpr float kNoData = std::numeric_limits<float>::quiet_NaN();
    std::uint64_t valid = 0;
    for (std::int64_t row0 = 0; row0 < height; row0 += stripRows) {
        const std::int64_t rows = std::min(stripRows, height - row0);
        const auto xSize = static_cast<int>(width);
        const auto ySize = static_cast<int>(rows);
        if (GDALRasterIO(band, GF_Read, 0, static_cast<int>(row0), xSize, ySize, values.data(),
                         xSize, ySize, GDT_Float64, 0, 0) != CE_None)
            throwGdalError(kStage,
                           "cannot read rows " + std::to_string(row0) + ".." +
                               std::to_string(row0 + rows - 1) + " of",
                           path);
        if (!allValid && GDALRasterIO(maskBand, GF_Read, 0, static_cast<int>(row0), xSize, ySize,
                                      mask.data(), xSize, ySize, GDT_Byte, 0, 0) != CE_None)
            throwGdalError(kStage,
                           "cannot read the mask of rows " + std::to_string(row0) + ".." +
                               std::to_string(row0 + rows - 1) + " of",
                           path);
        float* out = grid.z.data() + row0 * width;
        const std::size_t count = static_cast<std::size_t>(rows * width);
        for (std::size_t i = 0; i < count; ++i) {
            const double raw = values[i];
            if ((!allValid && mask[i] == 0) || std::isnan(raw)) {
                out[i] = kNoData;
                continue;
            }
            out[i] = static_cast<float>(applyScaleOffset ? raw * zScale + zOffset : raw);
            ++valid;
        }
        if (progress && !progress(static_cast<double>(row0 + rows) / static_cast<double>(height),
                                  "reading raster"))
            throw Cancelled(std::string(kStage) + ": cancelled while reading " + quoted(path));
    }
    const auto cellCount = static_cast<std::uint64_t>(grid.cellCount());
    if (valid == 0)
        throw InvalidInputError(std::string(kStage) + ": no valid cells in band " +
                                std::to_string(options.band) + " of " + quoted(path) + ": all " +
                                std::to_string(cellCount) + " cells are nodata, masked out or NaN");
    result.skippedCells = cellCount - valid;
    return result;
}

} // namespace terratin::io

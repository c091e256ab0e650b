/// @file
/// GdalRasterReader: one raster band to cell-centre points, read one block-row strip at a time.
///
/// Notation: (row, col) are 0-based cell indices from the raster's first stored row and column;
/// c[0..5] is GDAL's affine geotransform (GDAL Raster Data Model, "Affine GeoTransform").
/// Validity of a cell is decided by GDAL's mask band (RFC 15), which already implements the
/// nodata comparison in the band's own data type (a Float32 nodata of -3.4e38 is compared as the
/// float it was stored as, not as the double in the metadata), per-dataset masks and alpha
/// bands. A NaN value is skipped as well, whatever the mask says.

#include "terratin/io/raster_reader.hpp"

#include "terratin/error.hpp"
#include "terratin/io/gdal_error.hpp"

#include <cpl_conv.h>
#include <cpl_error.h>
#include <gdal.h>
#include <ogr_srs_api.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <new>
#include <stdexcept>
#include <string_view>

namespace terratin::io {

namespace {

constexpr std::string_view kStage = "GdalRasterReader";

/// A strip smaller than this many cells is grown by whole block rows. Rasters stored one row
/// per block (SRTM .hgt, ESRI ASCII grids, striped GeoTIFFs) would otherwise cost one RasterIO
/// call and one progress report per row. 2^18 cells is 2 MiB of Float64 plus 256 KiB of mask,
/// small next to the 32 bytes per cell of the result.
constexpr std::int64_t kMinStripCells = std::int64_t{1} << 18;

/// The affine transform at fractional pixel position (col + 0.5, row + 0.5), evaluated in one
/// fixed order so that cellCentre() and the read loop give bit-identical coordinates.
inline Point2 affineCellCentre(const std::array<double, 6>& c, double row, double col) {
    const double px = col + 0.5;
    const double py = row + 0.5;
    return {c[0] + px * c[1] + py * c[2], c[3] + px * c[4] + py * c[5]};
}

struct DatasetCloser {
    void operator()(void* dataset) const { GDALClose(dataset); }
};
using DatasetPtr = std::unique_ptr<void, DatasetCloser>;

struct CplFree {
    void operator()(char* text) const { CPLFree(text); }
};

std::string quoted(const std::string& path) {
    return "'" + path + "'";
}

/// The dataset's CRS as WKT2:2019, falling back to WKT1 for a CRS that WKT2 export rejects;
/// empty when the dataset has none.
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
    const std::unique_ptr<char, CplFree> owned(raw);
    return owned ? std::string(owned.get()) : std::string();
}

} // namespace

Point2 GeoTransform::cellCentre(std::int64_t row, std::int64_t col) const {
    return affineCellCentre(c, static_cast<double>(row), static_cast<double>(col));
}

RasterPoints readRasterPoints(const std::string& path, const RasterReadOptions& options,
                              const ProgressCallback& progress) {
    initialiseGdal();

    // Open: any raster driver; GDAL_OF_VERBOSE_ERROR makes "not recognised" an error message.
    CPLErrorReset();
    const DatasetPtr dataset(GDALOpenEx(path.c_str(), GDAL_OF_RASTER | GDAL_OF_VERBOSE_ERROR,
                                        nullptr, nullptr, nullptr));
    if (!dataset)
        throwGdalError(kStage, "cannot open raster", path);
    GDALDatasetH ds = dataset.get();

    // Band: 1-based, checked against what the file has.
    const int bandCount = GDALGetRasterCount(ds);
    if (bandCount == 0)
        throw InvalidInputError(std::string(kStage) + ": " + quoted(path) +
                                " has no raster bands (a container of subdatasets? open one "
                                "of them by its SUBDATASET name)");
    if (options.band < 1 || options.band > bandCount)
        throw InvalidInputError(std::string(kStage) + ": band " + std::to_string(options.band) +
                                " does not exist in " + quoted(path) + ", which has " +
                                std::to_string(bandCount) + " band(s) numbered from 1");
    GDALRasterBandH band = GDALGetRasterBand(ds, options.band);
    if (band == nullptr)
        throwGdalError(kStage, "cannot access band " + std::to_string(options.band) + " of", path);

    RasterPoints result;
    result.width = GDALGetRasterXSize(ds);
    result.height = GDALGetRasterYSize(ds);
    const std::int64_t width = result.width;
    const std::int64_t height = result.height;

    // Geotransform: without one GDAL reports failure; we keep its default (0,1,0,0,0,1) so that
    // cell (row, col) has centre (col + 0.5, row + 0.5) in pixel units.
    std::array<double, 6> c{0.0, 1.0, 0.0, 0.0, 0.0, 1.0};
    if (GDALGetGeoTransform(ds, c.data()) != CE_None)
        c = {0.0, 1.0, 0.0, 0.0, 0.0, 1.0};
    CPLErrorReset();
    result.geoTransform.c = c;
    result.crsWkt = crsAsWkt(ds);

    // z = raw * scale + offset only when the band declares either; otherwise z is raw exactly.
    int hasScale = 0;
    int hasOffset = 0;
    const double scale = GDALGetRasterScale(band, &hasScale);
    const double offset = GDALGetRasterOffset(band, &hasOffset);
    const bool applyScaleOffset = hasScale != 0 || hasOffset != 0;
    const double zScale = hasScale != 0 ? scale : 1.0;
    const double zOffset = hasOffset != 0 ? offset : 0.0;

    // Mask: GMF_ALL_VALID needs no mask read; anything else (nodata, per-dataset mask, alpha) is
    // read from GDAL's mask band, where 0 means "not valid".
    const int maskFlags = GDALGetMaskFlags(band);
    const bool allValid = (maskFlags & GMF_ALL_VALID) != 0;
    GDALRasterBandH maskBand = allValid ? nullptr : GDALGetMaskBand(band);
    if (!allValid && maskBand == nullptr)
        throwGdalError(kStage,
                       "cannot get the mask of band " + std::to_string(options.band) + " of", path);

    // Strips: whole rows, a multiple of the natural block height, grown to kMinStripCells.
    int blockXSize = 0;
    int blockYSize = 0;
    GDALGetBlockSize(band, &blockXSize, &blockYSize);
    const std::int64_t blockRows =
        std::clamp<std::int64_t>(blockYSize, 1, std::max<std::int64_t>(height, 1));
    const std::int64_t stripCellsPerBlockRow = std::max<std::int64_t>(width * blockRows, 1);
    const std::int64_t blockRowsPerStrip =
        std::max<std::int64_t>(1, kMinStripCells / stripCellsPerBlockRow);
    const std::int64_t stripRows =
        std::min(std::max<std::int64_t>(height, 1), blockRows * blockRowsPerStrip);

    // The result is at most one point per cell: reserving that avoids every reallocation, and
    // the excess (nodata frames) is released at the end when it is large.
    const auto cellCount = static_cast<std::uint64_t>(width) * static_cast<std::uint64_t>(height);
    std::vector<double> values;
    std::vector<std::uint8_t> mask;
    try {
        result.points.reserve(cellCount);
        result.cellIndex.reserve(cellCount);
        values.resize(static_cast<std::size_t>(stripRows * width));
        if (!allValid)
            mask.assign(values.size(), 0);
    } catch (const std::bad_alloc&) {
        throw InvalidInputError(std::string(kStage) + ": " + quoted(path) + " has " +
                                std::to_string(width) + " x " + std::to_string(height) +
                                " cells, too many to hold in memory as points");
    } catch (const std::length_error&) {
        throw InvalidInputError(std::string(kStage) + ": " + quoted(path) + " has " +
                                std::to_string(width) + " x " + std::to_string(height) +
                                " cells, too many to hold in memory as points");
    }

    for (std::int64_t row0 = 0; row0 < height; row0 += stripRows) {
        const std::int64_t rows = std::min(stripRows, height - row0);
        const auto xSize = static_cast<int>(width);
        const auto ySize = static_cast<int>(rows);
        const auto yOff = static_cast<int>(row0);

        // Read the strip's values (as Float64) and, unless all valid, its mask.
        if (GDALRasterIO(band, GF_Read, 0, yOff, xSize, ySize, values.data(), xSize, ySize,
                         GDT_Float64, 0, 0) != CE_None)
            throwGdalError(kStage,
                           "cannot read rows " + std::to_string(row0) + ".." +
                               std::to_string(row0 + rows - 1) + " of band " +
                               std::to_string(options.band) + " of",
                           path);
        if (!allValid && GDALRasterIO(maskBand, GF_Read, 0, yOff, xSize, ySize, mask.data(), xSize,
                                      ySize, GDT_Byte, 0, 0) != CE_None)
            throwGdalError(kStage,
                           "cannot read the mask of rows " + std::to_string(row0) + ".." +
                               std::to_string(row0 + rows - 1) + " of band " +
                               std::to_string(options.band) + " of",
                           path);

        // Keep valid, non-NaN cells in row-major order.
        for (std::int64_t r = 0; r < rows; ++r) {
            const std::int64_t row = row0 + r;
            const double* rowValues = values.data() + r * width;
            const std::uint8_t* rowMask = allValid ? nullptr : mask.data() + r * width;
            for (std::int64_t col = 0; col < width; ++col) {
                const double raw = rowValues[col];
                if ((rowMask != nullptr && rowMask[col] == 0) || std::isnan(raw)) {
                    ++result.skippedCells;
                    continue;
                }
                const Point2 centre =
                    affineCellCentre(c, static_cast<double>(row), static_cast<double>(col));
                const double z = applyScaleOffset ? raw * zScale + zOffset : raw;
                result.points.push_back({centre.x, centre.y, z});
                result.cellIndex.push_back(static_cast<std::uint64_t>(row * width + col));
            }
        }

        if (progress) {
            const double fraction = static_cast<double>(row0 + rows) / static_cast<double>(height);
            if (!progress(fraction, "reading raster"))
                throw Cancelled(std::string(kStage) + ": cancelled while reading " + quoted(path));
        }
    }

    if (result.points.empty())
        throw InvalidInputError(std::string(kStage) + ": no valid cells in band " +
                                std::to_string(options.band) + " of " + quoted(path) + ": all " +
                                std::to_string(cellCount) + " cells are nodata, masked out or NaN");

    // Give back the reservation for skipped cells when it is a sizeable share (over a quarter).
    if (result.skippedCells > cellCount / 4) {
        result.points.shrink_to_fit();
        result.cellIndex.shrink_to_fit();
    }
    return result;
}

} // namespace terratin::io

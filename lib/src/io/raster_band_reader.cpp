#include "raster_band_reader.hpp"

#include "terratin/error.hpp"
#include "terratin/io/gdal_error.hpp"

#include <cpl_conv.h>
#include <cpl_error.h>
#include <gdal.h>
#include <ogr_srs_api.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <new>
#include <stdexcept>
#include <vector>

namespace terratin::io::detail {

namespace {

/// A strip smaller than this many cells is grown by whole block rows. Rasters stored one row
/// per block (SRTM .hgt, ESRI ASCII grids, striped GeoTIFFs) would otherwise cost one RasterIO
/// call and one progress report per row. 2^18 cells is 2 MiB of Float64 plus 256 KiB of mask.
constexpr std::int64_t kMinStripCells = std::int64_t{1} << 18;

struct CplFree {
    void operator()(char* text) const { CPLFree(text); }
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
    const std::unique_ptr<char, CplFree> owned(raw);
    return owned ? std::string(owned.get()) : std::string();
}

} // namespace

struct RasterBandReader::Dataset {
    GDALDatasetH handle = nullptr;
    GDALRasterBandH band = nullptr;
    ~Dataset() {
        if (handle != nullptr)
            GDALClose(handle);
    }
};

RasterBandReader::RasterBandReader(const std::string& path, int band, std::string_view stage)
    : m_dataset(std::make_unique<Dataset>()), m_path(path), m_stage(stage), m_band(band) {
    initialiseGdal();
    // Any raster driver; GDAL_OF_VERBOSE_ERROR makes "not recognised" an error message.
    CPLErrorReset();
    m_dataset->handle = GDALOpenEx(path.c_str(), GDAL_OF_RASTER | GDAL_OF_VERBOSE_ERROR, nullptr,
                                   nullptr, nullptr);
    if (m_dataset->handle == nullptr)
        throwGdalError(m_stage, "cannot open raster", path);
    GDALDatasetH ds = m_dataset->handle;

    const int bandCount = GDALGetRasterCount(ds);
    if (bandCount == 0)
        throw InvalidInputError(m_stage + ": " + quotedPath() +
                                " has no raster bands (a container of subdatasets? open one "
                                "of them by its SUBDATASET name)");
    if (band < 1 || band > bandCount)
        throw InvalidInputError(m_stage + ": band " + std::to_string(band) + " does not exist in " +
                                quotedPath() + ", which has " + std::to_string(bandCount) +
                                " band(s) numbered from 1");
    m_dataset->band = GDALGetRasterBand(ds, band);
    if (m_dataset->band == nullptr)
        throwGdalError(m_stage, "cannot access band " + std::to_string(band) + " of", path);

    m_width = GDALGetRasterXSize(ds);
    m_height = GDALGetRasterYSize(ds);
    // Without a geotransform GDAL reports failure and we keep the default.
    if (GDALGetGeoTransform(ds, m_geoTransform.data()) != CE_None)
        m_geoTransform = {0.0, 1.0, 0.0, 0.0, 0.0, 1.0};
    CPLErrorReset();
    m_crsWkt = crsAsWkt(ds);
}

RasterBandReader::~RasterBandReader() = default;

std::uint64_t RasterBandReader::readStrips(const StripVisitor& visit,
                                           const ProgressCallback& progress) {
    GDALRasterBandH band = m_dataset->band;
    int hasScale = 0;
    int hasOffset = 0;
    const double scale = GDALGetRasterScale(band, &hasScale);
    const double offset = GDALGetRasterOffset(band, &hasOffset);
    const bool applyScaleOffset = hasScale != 0 || hasOffset != 0;
    const double zScale = hasScale != 0 ? scale : 1.0;
    const double zOffset = hasOffset != 0 ? offset : 0.0;

    // GMF_ALL_VALID needs no mask read; anything else (nodata, per-dataset mask, alpha) is read
    // from GDAL's mask band, where 0 means "not valid".
    const bool allValid = (GDALGetMaskFlags(band) & GMF_ALL_VALID) != 0;
    GDALRasterBandH maskBand = allValid ? nullptr : GDALGetMaskBand(band);
    if (!allValid && maskBand == nullptr)
        throwGdalError(m_stage, "cannot get the mask of band " + std::to_string(m_band) + " of",
                       m_path);

    int blockXSize = 0;
    int blockYSize = 0;
    GDALGetBlockSize(band, &blockXSize, &blockYSize);
    const std::int64_t rowsAtLeast = std::max<std::int64_t>(m_height, 1);
    const std::int64_t blockRows = std::clamp<std::int64_t>(blockYSize, 1, rowsAtLeast);
    const std::int64_t blockRowsPerStrip = std::max<std::int64_t>(
        1, kMinStripCells / std::max<std::int64_t>(m_width * blockRows, 1));
    const std::int64_t stripRows = std::min(rowsAtLeast, blockRows * blockRowsPerStrip);

    std::vector<double> values;
    std::vector<std::uint8_t> mask;
    try {
        values.resize(static_cast<std::size_t>(stripRows * m_width));
        if (!allValid)
            mask.assign(values.size(), 0);
    } catch (const std::bad_alloc&) {
        throw InvalidInputError(m_stage + ": " + quotedPath() + " has rows of " +
                                std::to_string(m_width) + " cells, too long to read");
    }

    constexpr double kInvalid = std::numeric_limits<double>::quiet_NaN();
    std::uint64_t valid = 0;
    for (std::int64_t row0 = 0; row0 < m_height; row0 += stripRows) {
        const std::int64_t rows = std::min(stripRows, m_height - row0);
        const auto xSize = static_cast<int>(m_width);
        const auto ySize = static_cast<int>(rows);
        const auto yOff = static_cast<int>(row0);
        const std::string rowsText = "rows " + std::to_string(row0) + ".." +
                                     std::to_string(row0 + rows - 1) + " of band " +
                                     std::to_string(m_band) + " of";
        if (GDALRasterIO(band, GF_Read, 0, yOff, xSize, ySize, values.data(), xSize, ySize,
                         GDT_Float64, 0, 0) != CE_None)
            throwGdalError(m_stage, "cannot read " + rowsText, m_path);
        if (!allValid && GDALRasterIO(maskBand, GF_Read, 0, yOff, xSize, ySize, mask.data(), xSize,
                                      ySize, GDT_Byte, 0, 0) != CE_None)
            throwGdalError(m_stage, "cannot read the mask of " + rowsText, m_path);

        const std::size_t count = static_cast<std::size_t>(rows * m_width);
        for (std::size_t i = 0; i < count; ++i) {
            double& z = values[i];
            if ((!allValid && mask[i] == 0) || std::isnan(z)) {
                z = kInvalid;
                continue;
            }
            if (applyScaleOffset)
                z = z * zScale + zOffset;
            ++valid;
        }
        visit(row0, std::span<const double>(values.data(), count));

        if (progress &&
            !progress(static_cast<double>(row0 + rows) / static_cast<double>(m_height),
                      "reading raster"))
            throw Cancelled(m_stage + ": cancelled while reading " + quotedPath());
    }
    return valid;
}

} // namespace terratin::io::detail

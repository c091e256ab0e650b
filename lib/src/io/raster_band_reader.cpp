#include "raster_band_reader.hpp"

#include "ascii_pgm.hpp"

#include "terratin/error.hpp"
#include "terratin/gdal_error.hpp"
#include "terratin/geometry/height_grid.hpp"

#include <cpl_conv.h>
#include <cpl_error.h>
#include <cpl_string.h>
#include <gdal.h>
#include <ogr_srs_api.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
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

/// Room left beside a strip's blocks for GDAL's own working memory while it decodes them
/// (decompressor state and buffers: zlib's is under 300 KiB, ZSTD's and LZMA's a few MiB).
constexpr std::size_t kGdalWorkingBytes = std::size_t{8} << 20;

/// Whether `bytes` can be allocated now. GDAL 3.6 does not check every allocation on its
/// RasterIO path: when the address space runs out (ulimit -v) it dereferences a null block and
/// the process dies of SIGSEGV instead of reporting an error. Allocating what the next read
/// will need, and giving it straight back, turns that into an error we can report.
bool canAllocate(std::size_t bytes) {
    // volatile: the compiler may not elide an allocation whose result it must store.
    void* volatile probe = std::malloc(bytes);
    const bool ok = probe != nullptr;
    std::free(probe);
    return ok;
}

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

/// The first bytes of the file at `path`; empty when it is not a readable file (a /vsi path, a
/// connection string: GDAL opens those).
std::string fileStart(const std::string& path) {
    std::FILE* file = std::fopen(path.c_str(), "rb");
    if (file == nullptr)
        return {};
    char bytes[4] = {};
    const std::size_t got = std::fread(bytes, 1, sizeof bytes, file);
    std::fclose(file);
    return std::string(bytes, got);
}

/// The subdataset names GDAL lists for a container ("GPKG:file.gpkg:table"...), in its order.
std::vector<std::string> subdatasetNames(GDALDatasetH dataset) {
    std::vector<std::string> names;
    char** metadata = GDALGetMetadata(dataset, "SUBDATASETS");
    for (int i = 1;; ++i) {
        const std::string key = "SUBDATASET_" + std::to_string(i) + "_NAME";
        const char* name = CSLFetchNameValue(metadata, key.c_str());
        if (name == nullptr)
            break;
        names.emplace_back(name);
    }
    return names;
}

/// Why a container of subdatasets cannot be read as it is, with the names that can.
std::string subdatasetAdvice(const std::vector<std::string>& names) {
    if (names.empty())
        return "has no raster bands";
    constexpr std::size_t kNamesShown = 4;
    std::string text = "holds " + std::to_string(names.size()) +
                       " rasters (subdatasets), not one: give one of them as the input by its "
                       "name, ";
    for (std::size_t i = 0; i < std::min(names.size(), kNamesShown); ++i)
        text += (i == 0 ? "'" : ", '") + names[i] + "'";
    if (names.size() > kNamesShown)
        text +=
            " and " + std::to_string(names.size() - kNamesShown) + " more (gdalinfo lists them)";
    return text;
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
    // GDAL's PNM driver reads binary PGMs only; the plain (ASCII) kind is read here.
    m_dataset->handle = isAsciiPgm(fileStart(path))
                            ? openAsciiPgm(path, m_stage)
                            : GDALOpenEx(path.c_str(), GDAL_OF_RASTER | GDAL_OF_VERBOSE_ERROR,
                                         nullptr, nullptr, nullptr);
    if (m_dataset->handle == nullptr)
        throwGdalError(m_stage, "cannot open raster", path, "GDAL recognises no raster in it");
    GDALDatasetH ds = m_dataset->handle;

    const int bandCount = GDALGetRasterCount(ds);
    if (bandCount == 0)
        throw InvalidInputError(m_stage + ": " + quotedPath() + " " +
                                subdatasetAdvice(subdatasetNames(ds)));
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
    if (const std::string problem = geoTransformProblem(m_geoTransform, m_width, m_height);
        !problem.empty())
        throw InvalidInputError(m_stage + ": the geotransform " + geoTransformText(m_geoTransform) +
                                " of " + quotedPath() + " " + problem +
                                "; fix its georeferencing (gdal_edit.py -a_ullr or -unsetgt)");
    CPLErrorReset();
    m_crsWkt = crsAsWkt(ds);
}

RasterBandReader::~RasterBandReader() = default;

RasterBandReader::BandRules RasterBandReader::bandRules() const {
    GDALRasterBandH band = m_dataset->band;
    BandRules rules;
    int hasScale = 0;
    int hasOffset = 0;
    const double scale = GDALGetRasterScale(band, &hasScale);
    const double offset = GDALGetRasterOffset(band, &hasOffset);
    rules.applyScaleOffset = hasScale != 0 || hasOffset != 0;
    rules.scale = hasScale != 0 ? scale : 1.0;
    rules.offset = hasOffset != 0 ? offset : 0.0;
    // GMF_ALL_VALID needs no mask read; anything else (nodata, per-dataset mask, alpha) is read
    // from GDAL's mask band, where 0 means "not valid".
    rules.allValid = (GDALGetMaskFlags(band) & GMF_ALL_VALID) != 0;
    rules.mask = rules.allValid ? nullptr : GDALGetMaskBand(band);
    if (!rules.allValid && rules.mask == nullptr)
        throwGdalError(m_stage, "cannot get the mask of band " + std::to_string(m_band) + " of",
                       m_path);
    return rules;
}

std::uint64_t RasterBandReader::readCells(const BandRules& rules, const CellBox& box,
                                          std::vector<double>& values,
                                          std::vector<std::uint8_t>& mask) const {
    const std::string columnsText = box.columns == m_width
                                        ? std::string()
                                        : ", columns " + std::to_string(box.firstColumn) + ".." +
                                              std::to_string(box.firstColumn + box.columns - 1);
    const std::string cellsText = "rows " + std::to_string(box.firstRow) + ".." +
                                  std::to_string(box.firstRow + box.rows - 1) + columnsText +
                                  " of band " + std::to_string(m_band) + " of";
    const auto xOff = static_cast<int>(box.firstColumn);
    const auto yOff = static_cast<int>(box.firstRow);
    const auto xSize = static_cast<int>(box.columns);
    const auto ySize = static_cast<int>(box.rows);
    if (GDALRasterIO(m_dataset->band, GF_Read, xOff, yOff, xSize, ySize, values.data(), xSize,
                     ySize, GDT_Float64, 0, 0) != CE_None)
        throwGdalError(m_stage, "cannot read " + cellsText, m_path);
    if (!rules.allValid && GDALRasterIO(rules.mask, GF_Read, xOff, yOff, xSize, ySize, mask.data(),
                                        xSize, ySize, GDT_Byte, 0, 0) != CE_None)
        throwGdalError(m_stage, "cannot read the mask of " + cellsText, m_path);

    constexpr double kInvalid = std::numeric_limits<double>::quiet_NaN();
    std::uint64_t valid = 0;
    const auto count = static_cast<std::size_t>(box.rows * box.columns);
    for (std::size_t i = 0; i < count; ++i) {
        double& z = values[i];
        if ((!rules.allValid && mask[i] == 0) || std::isnan(z)) {
            z = kInvalid;
            continue;
        }
        if (rules.applyScaleOffset)
            z = z * rules.scale + rules.offset;
        ++valid;
    }
    // Each block is read once: keeping it in GDAL's cache (up to 5% of RAM by default) would
    // only take memory from the points being built.
    GDALFlushRasterCache(m_dataset->band);
    if (rules.mask != nullptr)
        GDALFlushRasterCache(rules.mask);
    return valid;
}

std::uint64_t RasterBandReader::readStrips(const StripVisitor& visit,
                                           const ProgressCallback& progress) {
    GDALRasterBandH band = m_dataset->band;
    const BandRules rules = bandRules();
    int blockXSize = 0;
    int blockYSize = 0;
    GDALGetBlockSize(band, &blockXSize, &blockYSize);
    const std::int64_t rowsAtLeast = std::max<std::int64_t>(m_height, 1);
    const std::int64_t blockRows = std::clamp<std::int64_t>(blockYSize, 1, rowsAtLeast);
    const std::int64_t blockRowsPerStrip =
        std::max<std::int64_t>(1, kMinStripCells / std::max<std::int64_t>(m_width * blockRows, 1));
    const std::int64_t stripRows = std::min(rowsAtLeast, blockRows * blockRowsPerStrip);

    const auto outOfMemory = [&](std::uint64_t bytes) {
        return IoError(m_stage + ": out of memory reading " + quotedPath() + " (a strip of " +
                       std::to_string(stripRows) + " rows of " + std::to_string(m_width) +
                       " cells needs " + std::to_string((bytes >> 20) + 1) + " MiB more)");
    };
    std::vector<double> values;
    std::vector<std::uint8_t> mask;
    const std::uint64_t stripCells = static_cast<std::uint64_t>(stripRows * m_width);
    try {
        values.resize(static_cast<std::size_t>(stripCells));
        if (!rules.allValid)
            mask.assign(values.size(), 0);
    } catch (const std::bad_alloc&) {
        throw outOfMemory(stripCells * (rules.allValid ? 8 : 9));
    }
    // What GDAL allocates to read one strip: the blocks that cover it, in the band's own type,
    // and the mask's (one byte a cell), plus its working memory. Blocks may be wider than the
    // raster; a block row is never more than the strip.
    const std::int64_t blockColumns =
        blockXSize > 0 ? (m_width + blockXSize - 1) / blockXSize * blockXSize : m_width;
    const auto cellBytes =
        static_cast<std::uint64_t>(GDALGetDataTypeSizeBytes(GDALGetRasterDataType(band))) +
        (rules.allValid ? 0 : 1);
    const std::uint64_t gdalStripBytes =
        static_cast<std::uint64_t>(stripRows * blockColumns) * cellBytes + kGdalWorkingBytes;

    std::uint64_t valid = 0;
    for (std::int64_t row0 = 0; row0 < m_height; row0 += stripRows) {
        const std::int64_t rows = std::min(stripRows, m_height - row0);
        if (gdalStripBytes > std::numeric_limits<std::size_t>::max() ||
            !canAllocate(static_cast<std::size_t>(gdalStripBytes)))
            throw outOfMemory(gdalStripBytes);
        valid += readCells(rules, {row0, rows, 0, m_width}, values, mask);
        visit(row0,
              std::span<const double>(values.data(), static_cast<std::size_t>(rows * m_width)));

        if (progress && !progress(static_cast<double>(row0 + rows) / static_cast<double>(m_height),
                                  "reading raster"))
            throw Cancelled(m_stage + ": cancelled while reading " + quotedPath());
    }
    return valid;
}

std::vector<double> RasterBandReader::readWindow(const CellBox& box) {
    if (box.firstRow < 0 || box.firstColumn < 0 || box.rows < 1 || box.columns < 1 ||
        box.firstRow + box.rows > m_height || box.firstColumn + box.columns > m_width)
        throw std::out_of_range("RasterBandReader: a window outside the raster");
    const BandRules rules = bandRules();
    const auto count = static_cast<std::size_t>(box.rows * box.columns);
    std::vector<double> values(count);
    std::vector<std::uint8_t> mask(rules.allValid ? 0 : count);
    readCells(rules, box, values, mask);
    return values;
}

} // namespace terratin::io::detail

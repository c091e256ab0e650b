// Tests of GdalRasterReader (readRasterPoints): synthetic GeoTIFFs written here with GDAL, and
// the real DEMs of TERRATIN_SHARED_DEMS checked against an independent whole-raster read.

#include "terratin/error.hpp"
#include "terratin/gdal_error.hpp"
#include "terratin/io/raster_reader.hpp"

#include <cpl_conv.h>
#include <cpl_string.h>
#include <gdal.h>
#include <ogr_srs_api.h>

#include "temporary_directory.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <limits>
#include <memory>
#include <optional>
#include <random>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;
using terratin::Point3;
using terratin::io::GeoTransform;
using terratin::io::RasterPoints;
using terratin::io::RasterReadOptions;
using terratin::io::readRasterPoints;

using TempDir = terratin::test::TemporaryDirectory;

struct DatasetCloser {
    void operator()(void* dataset) const {
        if (dataset != nullptr)
            GDALClose(dataset);
    }
};
using DatasetPtr = std::unique_ptr<void, DatasetCloser>;

/// What a synthetic GeoTIFF looks like; bands hold `values[band]` in row-major order.
struct TiffSpec {
    int width = 0;
    int height = 0;
    GDALDataType type = GDT_Float32;
    std::vector<std::vector<double>> values;
    std::optional<std::array<double, 6>> geoTransform;
    std::optional<double> noData;
    std::optional<double> scale;
    std::optional<double> offset;
    int epsg = 0;
    /// 0: striped. Otherwise TILED=YES with this block size.
    int tileSize = 0;
};

/// Writes `spec` as a GeoTIFF at `path`.
void writeTiff(const std::string& path, const TiffSpec& spec) {
    terratin::initialiseGdal();
    GDALDriverH driver = GDALGetDriverByName("GTiff");
    ASSERT_NE(driver, nullptr);
    char** createOptions = nullptr;
    if (spec.tileSize > 0) {
        createOptions = CSLSetNameValue(createOptions, "TILED", "YES");
        createOptions =
            CSLSetNameValue(createOptions, "BLOCKXSIZE", std::to_string(spec.tileSize).c_str());
        createOptions =
            CSLSetNameValue(createOptions, "BLOCKYSIZE", std::to_string(spec.tileSize).c_str());
    }
    DatasetPtr dataset(GDALCreate(driver, path.c_str(), spec.width, spec.height,
                                  static_cast<int>(spec.values.size()), spec.type, createOptions));
    CSLDestroy(createOptions);
    ASSERT_NE(dataset, nullptr) << CPLGetLastErrorMsg();
    if (spec.geoTransform) {
        std::array<double, 6> transform = *spec.geoTransform;
        ASSERT_EQ(GDALSetGeoTransform(dataset.get(), transform.data()), CE_None);
    }
    if (spec.epsg != 0) {
        OGRSpatialReferenceH srs = OSRNewSpatialReference(nullptr);
        ASSERT_EQ(OSRImportFromEPSG(srs, spec.epsg), OGRERR_NONE);
        ASSERT_EQ(GDALSetSpatialRef(dataset.get(), srs), CE_None);
        OSRDestroySpatialReference(srs);
    }
    for (std::size_t b = 0; b < spec.values.size(); ++b) {
        GDALRasterBandH band = GDALGetRasterBand(dataset.get(), static_cast<int>(b) + 1);
        if (spec.noData) {
            ASSERT_EQ(GDALSetRasterNoDataValue(band, *spec.noData), CE_None);
        }
        if (spec.scale) {
            ASSERT_EQ(GDALSetRasterScale(band, *spec.scale), CE_None);
        }
        if (spec.offset) {
            ASSERT_EQ(GDALSetRasterOffset(band, *spec.offset), CE_None);
        }
        std::vector<double> data = spec.values[b];
        ASSERT_EQ(data.size(), static_cast<std::size_t>(spec.width) * spec.height);
        ASSERT_EQ(GDALRasterIO(band, GF_Write, 0, 0, spec.width, spec.height, data.data(),
                               spec.width, spec.height, GDT_Float64, 0, 0),
                  CE_None);
    }
}

/// Values row * 1000 + col + band * 1e6, distinct per cell and band.
std::vector<double> rampValues(int width, int height, int band = 0) {
    std::vector<double> values(static_cast<std::size_t>(width) * height);
    for (int row = 0; row < height; ++row)
        for (int col = 0; col < width; ++col)
            values[static_cast<std::size_t>(row) * width + col] = row * 1000.0 + col + band * 1e6;
    return values;
}

/// The affine formula of GDAL's data model, written out independently of the reader.
Point3 expectedCentre(const std::array<double, 6>& c, std::uint64_t index, int width) {
    const std::uint64_t col = index % static_cast<std::uint64_t>(width);
    const std::uint64_t row = index / static_cast<std::uint64_t>(width);
    const double px = static_cast<double>(col) + 0.5;
    const double py = static_cast<double>(row) + 0.5;
    return {c[0] + px * c[1] + py * c[2], c[3] + px * c[4] + py * c[5], 0.0};
}

/// Structural checks every result must pass: parallel arrays, strictly increasing cellIndex
/// (row-major order), counts adding up to the cell count.
void expectConsistent(const RasterPoints& result) {
    ASSERT_EQ(result.points.size(), result.cellIndex.size());
    const auto cells = static_cast<std::uint64_t>(result.width) * result.height;
    EXPECT_EQ(result.points.size() + result.skippedCells, cells);
    for (std::size_t i = 0; i < result.cellIndex.size(); ++i) {
        ASSERT_LT(result.cellIndex[i], cells);
        if (i > 0) {
            ASSERT_LT(result.cellIndex[i - 1], result.cellIndex[i]);
        }
    }
}

// --- Synthetic rasters ---------------------------------------------------------------------

TEST(GdalRasterReader, CellCentres_FollowFullAffineFormula_WhenGeoTransformIsRotated) {
    TempDir dir;
    TiffSpec spec;
    spec.width = 7;
    spec.height = 5;
    spec.values = {rampValues(7, 5)};
    spec.geoTransform = std::array<double, 6>{500000.25, 29.7, 4.1, 5200000.5, -3.3, -30.2};
    spec.epsg = 32632;
    const std::string path = dir.file("rotated.tif");
    ASSERT_NO_FATAL_FAILURE(writeTiff(path, spec));

    const RasterPoints result = readRasterPoints(path, {});
    expectConsistent(result);
    EXPECT_EQ(result.geoTransform.c, *spec.geoTransform);
    ASSERT_EQ(result.points.size(), 35U);
    for (std::size_t i = 0; i < result.points.size(); ++i) {
        const Point3 expected = expectedCentre(*spec.geoTransform, result.cellIndex[i], 7);
        EXPECT_EQ(result.points[i].x, expected.x) << "cell " << result.cellIndex[i];
        EXPECT_EQ(result.points[i].y, expected.y) << "cell " << result.cellIndex[i];
        const auto row = static_cast<std::int64_t>(result.cellIndex[i] / 7);
        const auto col = static_cast<std::int64_t>(result.cellIndex[i] % 7);
        EXPECT_EQ(result.geoTransform.cellCentre(row, col),
                  (terratin::Point2{result.points[i].x, result.points[i].y}));
    }
}

TEST(GdalRasterReader, RowsRunNorthward_WhenPixelHeightIsPositive) {
    TempDir dir;
    TiffSpec spec;
    spec.width = 4;
    spec.height = 6;
    spec.values = {rampValues(4, 6)};
    spec.geoTransform = std::array<double, 6>{4490657.5, 5.0, 0.0, 5320197.5, 0.0, 5.0};
    const std::string path = dir.file("bottom_up.tif");
    ASSERT_NO_FATAL_FAILURE(writeTiff(path, spec));

    const RasterPoints result = readRasterPoints(path, {});
    expectConsistent(result);
    ASSERT_EQ(result.points.size(), 24U);
    // The first stored row is the southernmost: centre y = origin + 0.5 * 5.
    EXPECT_EQ(result.points.front().y, 5320197.5 + 0.5 * 5.0);
    EXPECT_EQ(result.points.front().x, 4490657.5 + 0.5 * 5.0);
    EXPECT_GT(result.points.back().y, result.points.front().y);
    for (std::size_t i = 0; i < result.points.size(); ++i) {
        const Point3 expected = expectedCentre(*spec.geoTransform, result.cellIndex[i], 4);
        EXPECT_EQ(result.points[i].x, expected.x);
        EXPECT_EQ(result.points[i].y, expected.y);
        EXPECT_EQ(result.points[i].z, spec.values[0][result.cellIndex[i]]);
    }
}

TEST(GdalRasterReader, CentresArePixelCoordinates_WhenRasterHasNoGeoTransform) {
    TempDir dir;
    TiffSpec spec;
    spec.width = 3;
    spec.height = 2;
    spec.values = {rampValues(3, 2)};
    const std::string path = dir.file("no_transform.tif");
    ASSERT_NO_FATAL_FAILURE(writeTiff(path, spec));

    const RasterPoints result = readRasterPoints(path, {});
    expectConsistent(result);
    EXPECT_EQ(result.geoTransform.c, (std::array<double, 6>{0.0, 1.0, 0.0, 0.0, 0.0, 1.0}));
    EXPECT_TRUE(result.crsWkt.empty());
    ASSERT_EQ(result.points.size(), 6U);
    EXPECT_EQ(result.points[0], (Point3{0.5, 0.5, 0.0}));
    EXPECT_EQ(result.points[5], (Point3{2.5, 1.5, 1002.0}));
}

TEST(GdalRasterReader, CrsWktIsFilled_WhenRasterHasCrs) {
    TempDir dir;
    TiffSpec spec;
    spec.width = 2;
    spec.height = 2;
    spec.values = {rampValues(2, 2)};
    spec.geoTransform = std::array<double, 6>{600000.0, 10.0, 0.0, 5000000.0, 0.0, -10.0};
    spec.epsg = 26910;
    const std::string path = dir.file("crs.tif");
    ASSERT_NO_FATAL_FAILURE(writeTiff(path, spec));

    const RasterPoints result = readRasterPoints(path, {});
    ASSERT_FALSE(result.crsWkt.empty());
    OGRSpatialReferenceH srs = OSRNewSpatialReference(nullptr);
    char* wkt = const_cast<char*>(result.crsWkt.c_str());
    EXPECT_EQ(OSRImportFromWkt(srs, &wkt), OGRERR_NONE);
    EXPECT_STREQ(OSRGetAuthorityCode(srs, nullptr), "26910");
    OSRDestroySpatialReference(srs);
}

TEST(GdalRasterReader, NoDataCellsAreSkipped_WhenBandHasNoDataValue) {
    TempDir dir;
    TiffSpec spec;
    spec.width = 5;
    spec.height = 4;
    spec.type = GDT_Int16;
    spec.values = {rampValues(5, 4)};
    spec.noData = -9999.0;
    const std::vector<std::size_t> holes{0, 7, 13, 19};
    for (std::size_t hole : holes)
        spec.values[0][hole] = -9999.0;
    spec.geoTransform = std::array<double, 6>{0.0, 1.0, 0.0, 4.0, 0.0, -1.0};
    const std::string path = dir.file("nodata.tif");
    ASSERT_NO_FATAL_FAILURE(writeTiff(path, spec));

    const RasterPoints result = readRasterPoints(path, {});
    expectConsistent(result);
    EXPECT_EQ(result.skippedCells, holes.size());
    EXPECT_EQ(result.points.size(), 20U - holes.size());
    for (std::size_t i = 0; i < result.points.size(); ++i) {
        EXPECT_EQ(std::count(holes.begin(), holes.end(), result.cellIndex[i]), 0);
        EXPECT_EQ(result.points[i].z, spec.values[0][result.cellIndex[i]]);
    }
}

TEST(GdalRasterReader, LowestFloatNoDataIsSkipped_WhenFloat32BandUsesIt) {
    // -FLT_MAX as a double: the float nodata that GIS tools write most often.
    const double lowestFloat = -3.4028234663852886e38;
    TempDir dir;
    TiffSpec spec;
    spec.width = 4;
    spec.height = 3;
    spec.values = {rampValues(4, 3)};
    spec.values[0][2] = lowestFloat;
    spec.values[0][9] = lowestFloat;
    spec.noData = lowestFloat;
    const std::string path = dir.file("lowest_float.tif");
    ASSERT_NO_FATAL_FAILURE(writeTiff(path, spec));

    const RasterPoints result = readRasterPoints(path, {});
    expectConsistent(result);
    EXPECT_EQ(result.skippedCells, 2U);
    for (const Point3& point : result.points)
        EXPECT_GT(point.z, -1.0e38);
}

TEST(GdalRasterReader, NanCellsAreSkipped_WhenBandHasNoNoDataValue) {
    TempDir dir;
    TiffSpec spec;
    spec.width = 4;
    spec.height = 4;
    spec.values = {rampValues(4, 4)};
    spec.values[0][5] = std::numeric_limits<double>::quiet_NaN();
    spec.values[0][15] = std::numeric_limits<double>::quiet_NaN();
    const std::string path = dir.file("nan.tif");
    ASSERT_NO_FATAL_FAILURE(writeTiff(path, spec));

    const RasterPoints result = readRasterPoints(path, {});
    expectConsistent(result);
    EXPECT_EQ(result.skippedCells, 2U);
    for (std::size_t i = 0; i < result.points.size(); ++i) {
        EXPECT_FALSE(std::isnan(result.points[i].z));
        EXPECT_NE(result.cellIndex[i], 5U);
        EXPECT_NE(result.cellIndex[i], 15U);
    }
}

TEST(GdalRasterReader, MaskedCellsAreSkipped_WhenDatasetHasMaskBand) {
    TempDir dir;
    TiffSpec spec;
    spec.width = 6;
    spec.height = 3;
    spec.type = GDT_Int16;
    spec.values = {rampValues(6, 3)};
    const std::string path = dir.file("masked.tif");
    ASSERT_NO_FATAL_FAILURE(writeTiff(path, spec));
    {
        DatasetPtr dataset(GDALOpen(path.c_str(), GA_Update));
        ASSERT_NE(dataset, nullptr);
        GDALRasterBandH band = GDALGetRasterBand(dataset.get(), 1);
        ASSERT_EQ(GDALCreateDatasetMaskBand(dataset.get(), GMF_PER_DATASET), CE_None);
        std::vector<std::uint8_t> mask(18, 255);
        mask[0] = 0;
        mask[8] = 0;
        mask[17] = 0;
        ASSERT_EQ(GDALRasterIO(GDALGetMaskBand(band), GF_Write, 0, 0, 6, 3, mask.data(), 6, 3,
                               GDT_Byte, 0, 0),
                  CE_None);
    }

    const RasterPoints result = readRasterPoints(path, {});
    expectConsistent(result);
    EXPECT_EQ(result.skippedCells, 3U);
    EXPECT_EQ(result.cellIndex.front(), 1U);
    EXPECT_EQ(result.cellIndex.back(), 16U);
    for (std::size_t i = 0; i < result.points.size(); ++i) {
        EXPECT_NE(result.cellIndex[i], 8U);
        EXPECT_EQ(result.points[i].z, spec.values[0][result.cellIndex[i]]);
    }
}

TEST(GdalRasterReader, TransparentCellsAreSkipped_WhenDatasetHasAlphaBand) {
    TempDir dir;
    const std::string path = dir.file("alpha.tif");
    terratin::initialiseGdal();
    {
        char** createOptions = CSLSetNameValue(nullptr, "ALPHA", "YES");
        DatasetPtr dataset(GDALCreate(GDALGetDriverByName("GTiff"), path.c_str(), 3, 2, 2, GDT_Byte,
                                      createOptions));
        CSLDestroy(createOptions);
        ASSERT_NE(dataset, nullptr);
        std::vector<std::uint8_t> grey{10, 20, 30, 40, 50, 60};
        std::vector<std::uint8_t> alpha{255, 0, 255, 128, 255, 0};
        ASSERT_EQ(GDALRasterIO(GDALGetRasterBand(dataset.get(), 1), GF_Write, 0, 0, 3, 2,
                               grey.data(), 3, 2, GDT_Byte, 0, 0),
                  CE_None);
        ASSERT_EQ(GDALRasterIO(GDALGetRasterBand(dataset.get(), 2), GF_Write, 0, 0, 3, 2,
                               alpha.data(), 3, 2, GDT_Byte, 0, 0),
                  CE_None);
    }

    const RasterPoints result = readRasterPoints(path, {});
    expectConsistent(result);
    EXPECT_EQ(result.cellIndex, (std::vector<std::uint64_t>{0, 2, 3, 4}));
    EXPECT_EQ(result.points[2].z, 40.0);
}

TEST(GdalRasterReader, ElevationsAreScaledAndOffset_WhenBandHasScaleAndOffset) {
    TempDir dir;
    TiffSpec spec;
    spec.width = 5;
    spec.height = 3;
    spec.type = GDT_Int16;
    spec.values = {rampValues(5, 3)};
    spec.scale = 0.1;
    spec.offset = -250.5;
    const std::string path = dir.file("scaled.tif");
    ASSERT_NO_FATAL_FAILURE(writeTiff(path, spec));

    const RasterPoints result = readRasterPoints(path, {});
    expectConsistent(result);
    ASSERT_EQ(result.points.size(), 15U);
    for (std::size_t i = 0; i < result.points.size(); ++i) {
        const double raw = spec.values[0][result.cellIndex[i]];
        EXPECT_EQ(result.points[i].z, raw * 0.1 + -250.5);
    }
}

TEST(GdalRasterReader, ElevationsAreRawValuesExactly_WhenBandHasNoScaleOrOffset) {
    TempDir dir;
    TiffSpec spec;
    spec.width = 3;
    spec.height = 1;
    spec.type = GDT_Float64;
    spec.values = {{0.1, -0.0, 1234.56789012345}};
    const std::string path = dir.file("raw.tif");
    ASSERT_NO_FATAL_FAILURE(writeTiff(path, spec));

    const RasterPoints result = readRasterPoints(path, {});
    ASSERT_EQ(result.points.size(), 3U);
    EXPECT_EQ(result.points[0].z, 0.1);
    EXPECT_TRUE(std::signbit(result.points[1].z));
    EXPECT_EQ(result.points[2].z, 1234.56789012345);
}

TEST(GdalRasterReader, SecondBandIsRead_WhenBandIsTwo) {
    TempDir dir;
    TiffSpec spec;
    spec.width = 4;
    spec.height = 3;
    spec.values = {rampValues(4, 3, 0), rampValues(4, 3, 1), rampValues(4, 3, 2)};
    const std::string path = dir.file("three_bands.tif");
    ASSERT_NO_FATAL_FAILURE(writeTiff(path, spec));

    RasterReadOptions options;
    options.band = 2;
    const RasterPoints result = readRasterPoints(path, options);
    expectConsistent(result);
    ASSERT_EQ(result.points.size(), 12U);
    for (std::size_t i = 0; i < result.points.size(); ++i)
        EXPECT_EQ(result.points[i].z, spec.values[1][result.cellIndex[i]]);
}

TEST(GdalRasterReader, ThrowsInvalidInput_WhenBandIsOutOfRange) {
    TempDir dir;
    TiffSpec spec;
    spec.width = 2;
    spec.height = 2;
    spec.values = {rampValues(2, 2), rampValues(2, 2, 1)};
    const std::string path = dir.file("two_bands.tif");
    ASSERT_NO_FATAL_FAILURE(writeTiff(path, spec));

    for (int band : {0, -1, 3}) {
        RasterReadOptions options;
        options.band = band;
        try {
            (void)readRasterPoints(path, options);
            ADD_FAILURE() << "band " << band << " was accepted";
        } catch (const terratin::InvalidInputError& error) {
            const std::string message = error.what();
            EXPECT_EQ(message.rfind("GdalRasterReader: ", 0), 0U) << message;
            EXPECT_NE(message.find("band " + std::to_string(band)), std::string::npos);
            EXPECT_NE(message.find(path), std::string::npos) << message;
        }
    }
}

TEST(GdalRasterReader, ThrowsInvalidInput_WhenEveryCellIsNoData) {
    TempDir dir;
    TiffSpec spec;
    spec.width = 20;
    spec.height = 10;
    spec.type = GDT_Int16;
    spec.values = {std::vector<double>(200, -32768.0)};
    spec.noData = -32768.0;
    const std::string path = dir.file("all_nodata.tif");
    ASSERT_NO_FATAL_FAILURE(writeTiff(path, spec));

    try {
        (void)readRasterPoints(path, {});
        FAIL() << "an all-nodata raster was accepted";
    } catch (const terratin::InvalidInputError& error) {
        EXPECT_NE(std::string(error.what()).find("no valid cells"), std::string::npos)
            << error.what();
    }
}

TEST(GdalRasterReader, ThrowsIoErrorNamingPath_WhenFileIsMissing) {
    TempDir dir;
    const std::string path = dir.file("does_not_exist.tif");
    try {
        (void)readRasterPoints(path, {});
        FAIL() << "a missing file was accepted";
    } catch (const terratin::IoError& error) {
        const std::string message = error.what();
        EXPECT_EQ(message.rfind("GdalRasterReader: ", 0), 0U) << message;
        EXPECT_NE(message.find(path), std::string::npos) << message;
        EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    }
}

TEST(GdalRasterReader, ThrowsIoErrorNamingPath_WhenFileIsNotARaster) {
    TempDir dir;
    const std::string path = dir.file("notes.txt");
    {
        std::ofstream text(path);
        text << "These are not elevations.\nJust some words.\n";
    }
    try {
        (void)readRasterPoints(path, {});
        FAIL() << "a text file was accepted";
    } catch (const terratin::IoError& error) {
        const std::string message = error.what();
        EXPECT_EQ(message.rfind("GdalRasterReader: ", 0), 0U) << message;
        EXPECT_NE(message.find(path), std::string::npos) << message;
    }
}

/// The message of the terratin::Error that reading `path` raises, "" when none.
std::string readError(const std::string& path) {
    try {
        (void)readRasterPoints(path, {});
    } catch (const terratin::Error& error) {
        return error.what();
    }
    return {};
}

// A NaN or huge geotransform is refused by the reader, with the geotransform in the message;
// past it, the triangulator would report the points as "collinear".
TEST(GdalRasterReader, RefusesAnUnusableGeoTransform_WithItsOwnMessage_D20) {
    TempDir dir;
    const std::array<std::array<double, 6>, 3> transforms{{
        {0.0, 1e300, 0.0, 0.0, 0.0, -1e300},   // cells of infinite area
        {0.0, 1e-300, 0.0, 0.0, 0.0, -1e-300}, // cells of zero area
        {1e300, 1.0, 0.0, 0.0, 0.0, -1.0},     // centres beyond 1e15
    }};
    for (std::size_t i = 0; i < transforms.size(); ++i) {
        const std::string path = dir.file("gt" + std::to_string(i) + ".tif");
        TiffSpec spec;
        spec.width = 4;
        spec.height = 3;
        spec.values = {rampValues(4, 3)};
        spec.geoTransform = transforms[i];
        writeTiff(path, spec);
        const std::string message = readError(path);
        EXPECT_NE(message.find("the geotransform ("), std::string::npos) << message;
        EXPECT_EQ(message.find("collinear"), std::string::npos) << message;
    }
    // NaN, which GDAL's VRT driver takes from the text as it is.
    const std::string base = dir.file("base.tif");
    TiffSpec spec;
    spec.width = 4;
    spec.height = 3;
    spec.values = {rampValues(4, 3)};
    writeTiff(base, spec);
    const std::string vrt = dir.file("nan.vrt");
    {
        std::ofstream file(vrt);
        file << "<VRTDataset rasterXSize=\"4\" rasterYSize=\"3\">\n"
             << "  <GeoTransform>nan, 1, 0, 0, 0, -1</GeoTransform>\n"
             << "  <VRTRasterBand dataType=\"Float64\" band=\"1\"><SimpleSource>"
             << "<SourceFilename>" << base << "</SourceFilename><SourceBand>1</SourceBand>"
             << "</SimpleSource></VRTRasterBand>\n</VRTDataset>\n";
    }
    const std::string message = readError(vrt);
    EXPECT_NE(message.find("not a finite number"), std::string::npos) << message;
    EXPECT_NE(message.find("(nan, 1, 0, 0, 0, -1)"), std::string::npos) << message;
}

// The error for a GeoPackage of two rasters names each raster's subdataset as GDAL opens it
// (GPKG:path:table), and the name it gives opens, not "no such file or directory".
TEST(GdalRasterReader, AdvisesSubdatasetNamesThatOpen_ForATwoRasterGeoPackage_D16) {
    TempDir dir;
    const std::string gpkg = dir.file("two.gpkg");
    for (const char* table : {"a", "b"}) {
        const std::string tif = dir.file(std::string(table) + ".tif");
        TiffSpec spec;
        spec.width = table[0] == 'a' ? 5 : 4;
        spec.height = 3;
        spec.type = GDT_Byte;
        spec.values = {std::vector<double>(static_cast<std::size_t>(spec.width) * 3, 7.0)};
        spec.geoTransform = std::array<double, 6>{500000.0, 10.0, 0.0, 5000000.0, 0.0, -10.0};
        spec.epsg = 32633;
        writeTiff(tif, spec);
        DatasetPtr source(GDALOpen(tif.c_str(), GA_ReadOnly));
        ASSERT_NE(source, nullptr);
        char** options = CSLSetNameValue(nullptr, "RASTER_TABLE", table);
        if (table[0] == 'b')
            options = CSLSetNameValue(options, "APPEND_SUBDATASET", "YES");
        DatasetPtr copy(GDALCreateCopy(GDALGetDriverByName("GPKG"), gpkg.c_str(), source.get(),
                                       FALSE, options, nullptr, nullptr));
        CSLDestroy(options);
        ASSERT_NE(copy, nullptr) << CPLGetLastErrorMsg();
    }
    const std::string message = readError(gpkg);
    const std::string advised = "GPKG:" + gpkg + ":b";
    EXPECT_NE(message.find("'" + advised + "'"), std::string::npos) << message;
    const RasterPoints b = readRasterPoints(advised, {});
    EXPECT_EQ(b.width, 4);
    EXPECT_EQ(b.points.size(), 12u);
}

// An ASCII ("plain", P2) PGM, which GDAL 3.6 cannot read, is read as a heightfield without
// georeferencing, not as text with the bad number "P2".
TEST(GdalRasterReader, ReadsAPlainPgm_AsAGridWithoutGeoreferencing_D20) {
    TempDir dir;
    const std::string path = dir.file("small.pgm");
    {
        std::ofstream file(path);
        file << "P2\n# a comment\n3 2 # width height\n1000\n0 1 2\n3 4\n1000\n";
    }
    const RasterPoints result = readRasterPoints(path, {});
    expectConsistent(result);
    ASSERT_EQ(result.points.size(), 6u);
    EXPECT_TRUE(result.crsWkt.empty());
    const std::array<double, 6> identity{0.0, 1.0, 0.0, 0.0, 0.0, 1.0};
    EXPECT_EQ(result.geoTransform.c, identity);
    EXPECT_EQ(result.points[4].x, 1.5);
    EXPECT_EQ(result.points[4].y, 1.5);
    EXPECT_EQ(result.points[4].z, 4.0);
    EXPECT_EQ(result.points[5].z, 1000.0);

    const std::vector<std::pair<std::string, std::string>> broken{
        {"P2\n3 2\n10\n0 1 2\n3 4\n", "truncated"},
        {"P2\n3 2\n10\n0 1 2\n3 4 11\n", "above the maxval"},
        {"P2\n3 2\n70000\n0 1 2\n3 4 5\n", "maxval 70000"},
        {"P2\n3 -2\n10\n", "header"},
        {"P2\n3000000 3000000\n10\n0 1\n", "truncated"},
        {"P2\n3 2\n10\n0 1 2\n3 4 x\n", "sample 6"},
    };
    for (const auto& [text, expected] : broken) {
        {
            std::ofstream file(path, std::ios::trunc);
            file << text;
        }
        const std::string message = readError(path);
        EXPECT_NE(message.find(expected), std::string::npos) << text << ": " << message;
        EXPECT_NE(message.find("plain PGM"), std::string::npos) << message;
    }
}

// A GDAL message with a line break stays one line, so that the CLI's error is one line.
TEST(GdalError, KeepsMessagesOnOneLine_D20) {
    terratin::initialiseGdal();
    CPLErrorReset();
    CPLError(CE_Failure, CPLE_AppDefined, "first line\n  second line\r\nthird");
    try {
        terratin::throwGdalError("Stage", "cannot read", "a\nb.tif");
    } catch (const terratin::IoError& error) {
        EXPECT_STREQ(error.what(), "Stage: cannot read 'a b.tif': first line second line third");
    }
    EXPECT_EQ(terratin::oneLine("\n x \n\n y\t\n"), "x y");
    CPLErrorReset();
    EXPECT_EQ(terratin::lastGdalErrorMessage("the known cause"), "the known cause");
}

TEST(GdalRasterReader, EdgeBlocksAreRead_WhenTileSizeDoesNotDivideRaster) {
    TempDir dir;
    TiffSpec spec;
    spec.width = 53;
    spec.height = 37;
    spec.type = GDT_Int32;
    spec.tileSize = 16;
    spec.values = {rampValues(53, 37)};
    spec.noData = -1.0;
    // Holes in interior, edge and corner tiles.
    const std::vector<std::size_t> holes{0, 17 * 53 + 20, 36 * 53 + 52, 36 * 53 + 50, 20 * 53 + 52};
    for (std::size_t hole : holes)
        spec.values[0][hole] = -1.0;
    spec.geoTransform = std::array<double, 6>{100.0, 2.0, 0.0, 200.0, 0.0, -2.0};
    const std::string path = dir.file("tiled.tif");
    ASSERT_NO_FATAL_FAILURE(writeTiff(path, spec));
    {
        DatasetPtr dataset(GDALOpen(path.c_str(), GA_ReadOnly));
        int blockX = 0;
        int blockY = 0;
        GDALGetBlockSize(GDALGetRasterBand(dataset.get(), 1), &blockX, &blockY);
        ASSERT_EQ(blockX, 16);
        ASSERT_EQ(blockY, 16);
    }

    const RasterPoints result = readRasterPoints(path, {});
    expectConsistent(result);
    EXPECT_EQ(result.width, 53);
    EXPECT_EQ(result.height, 37);
    EXPECT_EQ(result.skippedCells, holes.size());
    std::size_t next = 0;
    for (std::size_t cell = 0; cell < spec.values[0].size(); ++cell) {
        if (std::count(holes.begin(), holes.end(), cell) != 0)
            continue;
        ASSERT_LT(next, result.points.size());
        EXPECT_EQ(result.cellIndex[next], cell);
        EXPECT_EQ(result.points[next].z, spec.values[0][cell]);
        const Point3 expected = expectedCentre(*spec.geoTransform, cell, 53);
        EXPECT_EQ(result.points[next].x, expected.x);
        EXPECT_EQ(result.points[next].y, expected.y);
        ++next;
    }
    EXPECT_EQ(next, result.points.size());
}

/// A raster whose 256-row tiles span more cells than the reader's smallest strip, so that it is
/// read in several strips whatever strip height the reader settles on.
TiffSpec multiStripSpec() {
    TiffSpec spec;
    spec.width = 1100;
    spec.height = 600;
    spec.type = GDT_Int16;
    spec.tileSize = 256;
    spec.values = {std::vector<double>(std::size_t{1100} * 600, 7.0)};
    return spec;
}

TEST(GdalRasterReader, ProgressRisesToOne_WhenReadingSeveralStrips) {
    TempDir dir;
    const TiffSpec spec = multiStripSpec();
    const std::string path = dir.file("progress.tif");
    ASSERT_NO_FATAL_FAILURE(writeTiff(path, spec));

    std::vector<double> fractions;
    const RasterPoints result =
        readRasterPoints(path, {}, [&fractions](double fraction, std::string_view message) {
            EXPECT_FALSE(message.empty());
            fractions.push_back(fraction);
            return true;
        });
    EXPECT_EQ(result.points.size(), 1100U * 600U);
    ASSERT_GT(fractions.size(), 1U);
    for (std::size_t i = 1; i < fractions.size(); ++i)
        EXPECT_GT(fractions[i], fractions[i - 1]);
    EXPECT_GT(fractions.front(), 0.0);
    EXPECT_EQ(fractions.back(), 1.0);
}

TEST(GdalRasterReader, ThrowsCancelled_WhenProgressReturnsFalse) {
    TempDir dir;
    const TiffSpec spec = multiStripSpec();
    const std::string path = dir.file("cancel.tif");
    ASSERT_NO_FATAL_FAILURE(writeTiff(path, spec));

    int calls = 0;
    try {
        (void)readRasterPoints(path, {}, [&calls](double, std::string_view) {
            ++calls;
            return calls < 2;
        });
        FAIL() << "the read went on after progress returned false";
    } catch (const terratin::Cancelled& error) {
        EXPECT_EQ(std::string(error.what()).rfind("GdalRasterReader: ", 0), 0U);
    }
    EXPECT_EQ(calls, 2);
}

// --- Real DEMs -----------------------------------------------------------------------------

/// A band read whole, independently of the reader, with its nodata value.
struct IndependentRead {
    int width = 0;
    int height = 0;
    GDALDataType type = GDT_Unknown;
    std::array<double, 6> geoTransform{};
    std::vector<double> values;
    std::optional<double> noData;

    /// Nodata compared in the band's own type (a Float32 band stores float values).
    [[nodiscard]] bool isNoData(double value) const {
        if (std::isnan(value))
            return true;
        if (!noData)
            return false;
        if (type == GDT_Float32)
            return static_cast<float>(value) == static_cast<float>(*noData);
        return value == *noData;
    }
};

std::string sharedDem(const std::string& name) {
    return (fs::path(TERRATIN_SHARED_DEMS) / name).string();
}

IndependentRead readWhole(const std::string& path) {
    terratin::initialiseGdal();
    IndependentRead read;
    DatasetPtr dataset(GDALOpen(path.c_str(), GA_ReadOnly));
    if (!dataset)
        return read;
    GDALRasterBandH band = GDALGetRasterBand(dataset.get(), 1);
    read.width = GDALGetRasterXSize(dataset.get());
    read.height = GDALGetRasterYSize(dataset.get());
    read.type = GDALGetRasterDataType(band);
    GDALGetGeoTransform(dataset.get(), read.geoTransform.data());
    int hasNoData = 0;
    const double noData = GDALGetRasterNoDataValue(band, &hasNoData);
    if (hasNoData != 0)
        read.noData = noData;
    read.values.resize(static_cast<std::size_t>(read.width) * read.height);
    if (GDALRasterIO(band, GF_Read, 0, 0, read.width, read.height, read.values.data(), read.width,
                     read.height, GDT_Float64, 0, 0) != CE_None)
        read.values.clear();
    return read;
}

/// Checks `result` against the independent read cell by cell: every non-nodata cell is a point
/// at the affine centre with the exact value, every nodata cell is skipped.
void expectMatchesIndependentRead(const RasterPoints& result, const IndependentRead& read) {
    ASSERT_FALSE(read.values.empty());
    expectConsistent(result);
    ASSERT_EQ(result.width, read.width);
    ASSERT_EQ(result.height, read.height);
    EXPECT_EQ(result.geoTransform.c, read.geoTransform);
    std::uint64_t noDataCells = 0;
    for (double value : read.values)
        noDataCells += read.isNoData(value) ? 1 : 0;
    EXPECT_EQ(result.skippedCells, noDataCells);
    EXPECT_EQ(result.points.size(), read.values.size() - noDataCells);
    std::size_t next = 0;
    for (std::size_t cell = 0; cell < read.values.size(); ++cell) {
        if (read.isNoData(read.values[cell]))
            continue;
        ASSERT_LT(next, result.points.size());
        ASSERT_EQ(result.cellIndex[next], cell);
        ASSERT_EQ(result.points[next].z, read.values[cell]) << "cell " << cell;
        const Point3 expected = expectedCentre(read.geoTransform, cell, read.width);
        ASSERT_EQ(result.points[next].x, expected.x) << "cell " << cell;
        ASSERT_EQ(result.points[next].y, expected.y) << "cell " << cell;
        ++next;
    }
}

TEST(GdalRasterReader, MtHoodValidCellsEqualCellsMinusNoData_WhenReadFromGeoTiff) {
    const std::string path = sharedDem("gdalraster__lf_elev_220_mt_hood_utm.tif");
    if (!fs::exists(path))
        GTEST_SKIP() << "real DEM not available: " << path;
    const RasterPoints result = readRasterPoints(path, {});
    const IndependentRead read = readWhole(path);
    EXPECT_EQ(result.width, 1013);
    EXPECT_EQ(result.height, 799);
    EXPECT_GT(result.skippedCells, 0U);
    EXPECT_FALSE(result.crsWkt.empty());
    expectMatchesIndependentRead(result, read);
}

TEST(GdalRasterReader, Dgm5RowsRunNorthward_WhenPixelHeightIsPositive) {
    const std::string path = sharedDem("pyterra__dgm5.tif");
    if (!fs::exists(path))
        GTEST_SKIP() << "real DEM not available: " << path;
    const RasterPoints result = readRasterPoints(path, {});
    const IndependentRead read = readWhole(path);
    ASSERT_GT(result.geoTransform.c[5], 0.0);
    EXPECT_GT(result.points.back().y, result.points.front().y);
    expectMatchesIndependentRead(result, read);
}

TEST(GdalRasterReader, VinschgauHasNoFloatNoDataPoint_WhenNoDataIsMinus3_4e38) {
    const std::string path = sharedDem("terra__elev_vinschgau.tif");
    if (!fs::exists(path))
        GTEST_SKIP() << "real DEM not available: " << path;
    const RasterPoints result = readRasterPoints(path, {});
    const IndependentRead read = readWhole(path);
    ASSERT_TRUE(read.noData.has_value());
    const double storedNoData = static_cast<float>(*read.noData);
    EXPECT_GT(result.skippedCells, 0U);
    for (const Point3& point : result.points) {
        ASSERT_NE(point.z, storedNoData);
        ASSERT_NE(point.z, *read.noData);
        ASSERT_GT(point.z, -1.0e38);
    }
    expectMatchesIndependentRead(result, read);
}

TEST(GdalRasterReader, EverestVoidsAreSkipped_WhenReadFromGeoTiff) {
    const std::string path = sharedDem("osgearth__mt_everest_90m.tif");
    if (!fs::exists(path))
        GTEST_SKIP() << "real DEM not available: " << path;
    const RasterPoints result = readRasterPoints(path, {});
    const IndependentRead read = readWhole(path);
    EXPECT_GT(result.skippedCells, 0U);
    for (const Point3& point : result.points)
        ASSERT_NE(point.z, -32768.0);
    expectMatchesIndependentRead(result, read);
}

TEST(GdalRasterReader, WestBijouAsciiGridHasCrs_WhenPrjFileIsBeside) {
    const std::string path = sharedDem("landlab__west_bijou_escarpment_snippet.asc");
    if (!fs::exists(path))
        GTEST_SKIP() << "real DEM not available: " << path;
    const RasterPoints result = readRasterPoints(path, {});
    const IndependentRead read = readWhole(path);
    EXPECT_EQ(result.width, 129);
    EXPECT_EQ(result.height, 67);
    EXPECT_FALSE(result.crsWkt.empty());
    expectMatchesIndependentRead(result, read);
}

TEST(GdalRasterReader, SrtmHgtIsGeoreferenced_WhenReadFromN44W072) {
    const std::string path = sharedDem("srtmpy__N44W072/N44W072.hgt");
    if (!fs::exists(path))
        GTEST_SKIP() << "real DEM not available: " << path;
    const RasterPoints result = readRasterPoints(path, {});
    const IndependentRead read = readWhole(path);
    EXPECT_EQ(result.width, 1201);
    EXPECT_EQ(result.height, 1201);
    EXPECT_FALSE(result.crsWkt.empty());
    // Cell centres lie in the 1-degree tile (plus half a cell of SRTM's overlapping edges).
    for (const Point3& point : result.points) {
        ASSERT_GE(point.x, -72.0);
        ASSERT_LE(point.x, -71.0);
        ASSERT_GE(point.y, 44.0);
        ASSERT_LE(point.y, 45.0);
    }
    expectMatchesIndependentRead(result, read);
}

} // namespace

// terratin-demgen: writes the deterministic synthetic DEM shipped in sample_dems/.
//
//   terratin-demgen OUTPUT.tif [WIDTH HEIGHT]
//
// The terrain is a sum of ridges and valleys from closed-form functions (no random numbers,
// so every platform writes the same cells): a ridge system running south-west to north-east,
// a round lake left as nodata (a real hole for the TIN) and a bowl. 10 m cells in
// WGS 84 / UTM zone 33N, Float32, nodata -9999.

#include "terratin/gdal_error.hpp"

#include <cpl_string.h>
#include <gdal_priv.h>
#include <ogr_spatialref.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <numbers>
#include <string>
#include <vector>

namespace {

constexpr double kCellSizeM = 10.0;
constexpr double kOriginEastingM = 455000.0;
constexpr double kOriginNorthingM = 5105000.0;
constexpr float kNodata = -9999.0F;
constexpr int kUtm33NorthEpsg = 32633;

// Elevation in metres at (u, v), both in [0, 1] across the raster.
double elevationM(double u, double v) {
    constexpr double pi = std::numbers::pi;
    const double ridges = 120.0 * std::sin(2.0 * pi * (1.7 * u + 1.1 * v)) *
                          (0.6 + 0.4 * std::cos(2.0 * pi * 0.8 * (u - v)));
    const double hills = 35.0 * std::sin(2.0 * pi * 5.0 * u) * std::sin(2.0 * pi * 4.0 * v);
    const double tilt = 300.0 * v + 80.0 * u;
    const double bowl = -150.0 * std::exp(-(std::pow(u - 0.7, 2) + std::pow(v - 0.3, 2)) / 0.02);
    return 800.0 + ridges + hills + tilt + bowl;
}

bool insideLake(double u, double v) {
    return std::pow((u - 0.25) / 0.08, 2) + std::pow((v - 0.7) / 0.06, 2) < 1.0;
}

} // namespace

int main(int argc, char** argv) {
    if (argc != 2 && argc != 4) {
        std::fprintf(stderr, "usage: terratin-demgen OUTPUT.tif [WIDTH HEIGHT]\n");
        return 2;
    }
    const std::string output = argv[1];
    const int width = argc == 4 ? std::atoi(argv[2]) : 320;
    const int height = argc == 4 ? std::atoi(argv[3]) : 240;
    if (width < 2 || height < 2) {
        std::fprintf(stderr, "terratin-demgen: WIDTH and HEIGHT must be at least 2\n");
        return 2;
    }
    terratin::initialiseGdal();

    GDALDriver* driver = GetGDALDriverManager()->GetDriverByName("GTiff");
    CPLStringList creationOptions;
    creationOptions.SetNameValue("COMPRESS", "DEFLATE");
    creationOptions.SetNameValue("PREDICTOR", "3");
    creationOptions.SetNameValue("TILED", "YES");
    GDALDataset* dataset =
        driver->Create(output.c_str(), width, height, 1, GDT_Float32, creationOptions.List());
    if (dataset == nullptr) {
        std::fprintf(stderr, "terratin-demgen: cannot create '%s': %s\n", output.c_str(),
                     terratin::lastGdalErrorMessage().c_str());
        return 1;
    }
    double geoTransform[6] = {kOriginEastingM, kCellSizeM, 0.0, kOriginNorthingM, 0.0, -kCellSizeM};
    dataset->SetGeoTransform(geoTransform);
    OGRSpatialReference srs;
    srs.importFromEPSG(kUtm33NorthEpsg);
    dataset->SetSpatialRef(&srs);

    std::vector<float> cells(static_cast<std::size_t>(width) * static_cast<std::size_t>(height));
    for (int row = 0; row < height; ++row) {
        for (int col = 0; col < width; ++col) {
            const double u = (col + 0.5) / width;
            const double v = 1.0 - (row + 0.5) / height; // v grows northwards
            // Centimetre precision, like a survey-grade DEM, keeps the file small.
            const float value =
                insideLake(u, v) ? kNodata
                                 : static_cast<float>(std::round(elevationM(u, v) * 100.0) / 100.0);
            cells[static_cast<std::size_t>(row) * static_cast<std::size_t>(width) +
                  static_cast<std::size_t>(col)] = value;
        }
    }
    GDALRasterBand* band = dataset->GetRasterBand(1);
    band->SetNoDataValue(kNodata);
    const CPLErr written = band->RasterIO(GF_Write, 0, 0, width, height, cells.data(), width,
                                          height, GDT_Float32, 0, 0);
    GDALClose(dataset);
    if (written != CE_None) {
        std::fprintf(stderr, "terratin-demgen: cannot write '%s': %s\n", output.c_str(),
                     terratin::lastGdalErrorMessage().c_str());
        return 1;
    }
    std::printf("wrote %s (%d x %d cells)\n", output.c_str(), width, height);
    return 0;
}

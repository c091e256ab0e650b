#include "constraint_test_data.hpp"

#include "terratin/gdal_error.hpp"

#include <gdal_priv.h>
#include <ogr_api.h>
#include <ogrsf_frmts.h>

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <iomanip>
#include <memory>

namespace terratin::test {

Point2 sampleCellCentre(int column, int row) {
    return {455005.0 + 10.0 * column, 5104995.0 - 10.0 * row};
}

std::vector<Point2> sampleLake() {
    return {{456100.5, 5103300.25},
            {457000.75, 5103150.5},
            {457400.25, 5103900.75},
            {456600.5, 5104400.25},
            {455900.25, 5103950.5}};
}

void writeVectorLayer(const std::filesystem::path& path, const std::string& layer,
                      const std::vector<std::string>& wkts, int epsg,
                      const std::vector<double>& levels, int levelType) {
    initialiseGdal();
    GDALDriver* driver = GetGDALDriverManager()->GetDriverByName("GPKG");
    const std::unique_ptr<GDALDataset> dataset(
        driver->Create(path.c_str(), 0, 0, 0, GDT_Unknown, nullptr));
    if (!dataset) {
        ADD_FAILURE() << "cannot create " << path;
        return;
    }
    OGRSpatialReference srs;
    srs.importFromEPSG(epsg);
    OGRLayer* created =
        dataset->CreateLayer(layer.c_str(), epsg != 0 ? &srs : nullptr, wkbUnknown, nullptr);
    if (levelType >= 0) {
        OGRFieldDefn field("level", static_cast<OGRFieldType>(levelType));
        EXPECT_EQ(created->CreateField(&field), OGRERR_NONE);
    }
    for (std::size_t i = 0; i < wkts.size(); ++i) {
        OGRFeature feature(created->GetLayerDefn());
        OGRGeometry* geometry = nullptr;
        EXPECT_EQ(OGRGeometryFactory::createFromWkt(wkts[i].c_str(), nullptr, &geometry),
                  OGRERR_NONE)
            << wkts[i];
        feature.SetGeometryDirectly(geometry);
        if (levelType >= 0 && i < levels.size() && !std::isnan(levels[i]))
            feature.SetField(0, levels[i]);
        EXPECT_EQ(created->CreateFeature(&feature), OGRERR_NONE);
    }
}

namespace {

std::string coordinates(const std::vector<Point2>& points, bool closed) {
    std::string text;
    for (std::size_t i = 0; i < points.size() + (closed ? 1 : 0); ++i) {
        const Point2& p = points[i % points.size()];
        text += (i > 0 ? ", " : "") + std::to_string(p.x) + " " + std::to_string(p.y);
    }
    return text;
}

} // namespace

std::string polygonWkt(const std::vector<Point2>& ring) {
    return "POLYGON ((" + coordinates(ring, true) + "))";
}

std::string lineWkt(const std::vector<Point2>& points) {
    return "LINESTRING (" + coordinates(points, false) + ")";
}

bool insideRing(const std::vector<Point2>& ring, Point2 p) {
    bool odd = false;
    for (std::size_t i = 0, j = ring.size() - 1; i < ring.size(); j = i++)
        if ((ring[i].y > p.y) != (ring[j].y > p.y) &&
            p.x < (ring[j].x - ring[i].x) * (p.y - ring[i].y) / (ring[j].y - ring[i].y) + ring[i].x)
            odd = !odd;
    return odd;
}

std::vector<float> readElevations(const std::filesystem::path& raster) {
    initialiseGdal();
    const std::unique_ptr<GDALDataset> dataset(
        GDALDataset::Open(raster.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY));
    if (!dataset) {
        ADD_FAILURE() << "cannot open " << raster;
        return {};
    }
    GDALRasterBand* band = dataset->GetRasterBand(1);
    const int width = dataset->GetRasterXSize();
    const int height = dataset->GetRasterYSize();
    std::vector<float> z(static_cast<std::size_t>(width) * static_cast<std::size_t>(height));
    EXPECT_EQ(
        band->RasterIO(GF_Read, 0, 0, width, height, z.data(), width, height, GDT_Float32, 0, 0),
        CE_None);
    int hasNoData = 0;
    const double noData = band->GetNoDataValue(&hasNoData);
    if (hasNoData != 0)
        for (float& value : z)
            if (value == static_cast<float>(noData))
                value = std::numeric_limits<float>::quiet_NaN();
    return z;
}

std::vector<Point2> validCellCentres(const std::filesystem::path& raster) {
    const std::vector<float> z = readElevations(raster);
    initialiseGdal();
    const std::unique_ptr<GDALDataset> dataset(
        GDALDataset::Open(raster.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY));
    if (!dataset)
        return {};
    double transform[6] = {};
    EXPECT_EQ(dataset->GetGeoTransform(transform), CE_None);
    const int width = dataset->GetRasterXSize();
    std::vector<Point2> centres;
    for (std::size_t cell = 0; cell < z.size(); ++cell)
        if (!std::isnan(z[cell])) {
            const auto column = static_cast<double>(cell % static_cast<std::size_t>(width));
            const auto row = static_cast<double>(cell / static_cast<std::size_t>(width));
            centres.push_back({transform[0] + (column + 0.5) * transform[1],
                               transform[3] + (row + 0.5) * transform[5]});
        }
    return centres;
}

HullOverlap hullOverlap(const std::vector<Point2>& points, const std::vector<Point2>& ring) {
    if (!OGRGeometryFactory::haveGEOS()) {
        ADD_FAILURE() << "GDAL has no GEOS";
        return {};
    }
    OGRMultiPoint cloud;
    for (const Point2& p : points) {
        OGRPoint point(p.x, p.y);
        cloud.addGeometry(&point);
    }
    const std::unique_ptr<OGRGeometry> hull(cloud.ConvexHull());
    OGRLinearRing boundary;
    for (std::size_t i = 0; i <= ring.size(); ++i)
        boundary.addPoint(ring[i % ring.size()].x, ring[i % ring.size()].y);
    OGRPolygon polygon;
    polygon.addRing(&boundary);
    const std::unique_ptr<OGRGeometry> overlap(polygon.Intersection(hull.get()));
    if (!hull || !overlap) {
        ADD_FAILURE() << "GEOS failed on the hull or its intersection";
        return {};
    }
    return {OGR_G_Area(OGRGeometry::ToHandle(hull.get())),
            OGR_G_Area(OGRGeometry::ToHandle(overlap.get()))};
}

void writeElevations(const std::filesystem::path& path, int width, int height, double x0, double y0,
                     double cellSize, std::vector<float> z) {
    initialiseGdal();
    GDALDriver* driver = GetGDALDriverManager()->GetDriverByName("GTiff");
    const std::unique_ptr<GDALDataset> dem(
        driver != nullptr ? driver->Create(path.c_str(), width, height, 1, GDT_Float32, nullptr)
                          : nullptr);
    if (!dem) {
        ADD_FAILURE() << "cannot create " << path;
        return;
    }
    double transform[6] = {x0, cellSize, 0.0, y0, 0.0, -cellSize};
    dem->SetGeoTransform(transform);
    OGRSpatialReference utm;
    utm.importFromEPSG(32633);
    dem->SetSpatialRef(&utm);
    constexpr float kNoData = -9999.0F;
    for (float& value : z)
        if (std::isnan(value))
            value = kNoData;
    GDALRasterBand* band = dem->GetRasterBand(1);
    band->SetNoDataValue(kNoData);
    EXPECT_EQ(
        band->RasterIO(GF_Write, 0, 0, width, height, z.data(), width, height, GDT_Float32, 0, 0),
        CE_None);
}

std::vector<Point2> writePlanePoints(const std::filesystem::path& path, int count,
                                     std::uint64_t seed) {
    std::ofstream text(path);
    std::vector<Point2> points;
    std::uint64_t state = seed;
    const auto next = [&] {
        state = state * 6364136223846793005ULL + 1442695040888963407ULL;
        return static_cast<double>(state >> 40) / 16777216.0 * 1000.0;
    };
    for (int i = 0; i < count; ++i) {
        const double x = next();
        const double y = next();
        text << std::setprecision(17) << x << ' ' << y << ' ' << x / 100.0 + y / 50.0 << '\n';
        points.push_back({x, y});
    }
    return points;
}

} // namespace terratin::test

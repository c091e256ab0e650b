// Tests of the CRS module: zone choice against GeographicLib's documented rules, zone CRSs,
// PROJ reprojection checked against GeographicLib's own UTM and by round trips (1 mm), and
// the SRTM tile N44W072 projected to UTM 19N with its elevations untouched.

#include "terratin/crs/reprojection.hpp"
#include "terratin/crs/utm_zone.hpp"
#include "terratin/error.hpp"
#include "terratin/io/raster_reader.hpp"

#include <GeographicLib/UTMUPS.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <random>

namespace terratin::crs {
namespace {

/// Round trips must come back within a millimetre, far finer than any DEM's cells; PROJ's tmerc
/// and merc are good to nanometres, so a failure means a real error, not rounding.
constexpr double kRoundTripToleranceM = 1e-3;

TEST(UtmZone, FollowsGeographicLibStandardZones) {
    EXPECT_EQ(standardUtmZone(-71.5, 44.5), (UtmZone{19, true}));
    EXPECT_EQ(standardUtmZone(-122.0, 45.0), (UtmZone{10, true}));
    EXPECT_EQ(standardUtmZone(151.2, -33.9), (UtmZone{56, false}));
    EXPECT_EQ(standardUtmZone(5.0, 60.0), (UtmZone{32, true}));  // Norway exception
    EXPECT_EQ(standardUtmZone(10.0, 75.0), (UtmZone{33, true})); // Svalbard exception
    EXPECT_EQ(standardUtmZone(0.0, 85.0), (UtmZone{0, true}));   // UPS north above 84
    EXPECT_EQ(standardUtmZone(0.0, -81.0), (UtmZone{0, false})); // UPS south below -80
    EXPECT_EQ(standardUtmZone(0.0, 85.0).name(), "UPS North");
    EXPECT_EQ(standardUtmZone(-71.5, 44.5).name(), "UTM zone 19N");
    EXPECT_THROW(standardUtmZone(0.0, 91.0), CrsError);
    EXPECT_THROW(standardUtmZone(NAN, 0.0), CrsError);
}

TEST(UtmZone, GivesEpsgCodesOnWgs84_AndKeepsOtherDatums) {
    const std::string wgs84 = crsFromUserInput("EPSG:4326", "test");
    EXPECT_EQ(describeCrs(utmZoneCrs({19, true}, wgs84)).code, "EPSG:32619");
    EXPECT_EQ(describeCrs(utmZoneCrs({56, false}, wgs84)).code, "EPSG:32756");
    EXPECT_EQ(describeCrs(utmZoneCrs({0, true}, wgs84)).code, "EPSG:32661");

    // NAD83: the zone on NAD83, in metres; projecting moves nothing through a datum shift, so
    // a NAD83 degree point lands where the NAD83 / UTM 19N (EPSG:26919) definition puts it.
    const std::string nad83 = crsFromUserInput("EPSG:4269", "test");
    const std::string zone = utmZoneCrs({19, true}, nad83);
    const CrsDescription description = describeCrs(zone);
    EXPECT_TRUE(description.projected);
    EXPECT_EQ(description.metresPerUnit, 1.0);
    const Point2 ours = Reprojector(nad83, zone).transform(Point2{-71.5, 44.5});
    const Point2 epsg =
        Reprojector(nad83, crsFromUserInput("EPSG:26919", "test")).transform(Point2{-71.5, 44.5});
    EXPECT_NEAR(ours.x, epsg.x, kRoundTripToleranceM);
    EXPECT_NEAR(ours.y, epsg.y, kRoundTripToleranceM);
}

TEST(Reprojection, MatchesGeographicLibUtm_WithinAMillimetre) {
    const Reprojector toUtm(crsFromUserInput("EPSG:4326", "test"),
                            crsFromUserInput("EPSG:32619", "test"));
    std::mt19937_64 random(7);
    std::uniform_real_distribution<double> lon(-72.0, -66.0);
    std::uniform_real_distribution<double> lat(0.5, 84.0);
    for (int i = 0; i < 1000; ++i) {
        const double longitude = lon(random);
        const double latitude = lat(random);
        const Point2 proj = toUtm.transform(Point2{longitude, latitude});
        int zone = 0;
        bool north = false;
        double x = 0.0;
        double y = 0.0;
        GeographicLib::UTMUPS::Forward(latitude, longitude, zone, north, x, y, 19);
        ASSERT_NEAR(proj.x, x, kRoundTripToleranceM) << longitude << ", " << latitude;
        ASSERT_NEAR(proj.y, y, kRoundTripToleranceM) << longitude << ", " << latitude;
    }
}

TEST(Reprojection, RoundTripsWithinAMillimetre) {
    struct Case {
        const char* source;
        const char* target;
        Point2 lower;
        Point2 upper;
    };
    // Projected corners, and the projected CRS each round trip is measured in.
    const Case cases[] = {
        {"EPSG:32619", "EPSG:3857", {250000, 4800000}, {750000, 5100000}},
        {"EPSG:32619", "EPSG:4326", {250000, 4800000}, {750000, 5100000}},
        {"EPSG:2992", "EPSG:32610", {5e5, 7e5}, {1.5e6, 1.2e6}},        // Oregon Lambert ft
        {"EPSG:3358", "EPSG:3857", {600000, 200000}, {700000, 250000}}, // NC State Plane m
    };
    std::mt19937_64 random(3);
    for (const Case& c : cases) {
        const Reprojector forward(crsFromUserInput(c.source, "test"),
                                  crsFromUserInput(c.target, "test"));
        const Reprojector back = forward.inverse();
        std::uniform_real_distribution<double> x(c.lower.x, c.upper.x);
        std::uniform_real_distribution<double> y(c.lower.y, c.upper.y);
        std::vector<Point3> points;
        for (int i = 0; i < 1000; ++i)
            points.push_back({x(random), y(random), static_cast<double>(i) + 0.125});
        std::vector<Point3> moved = points;
        forward.transform(moved);
        back.transform(moved);
        const double unitM = describeCrs(crsFromUserInput(c.source, "test")).metresPerUnit;
        for (std::size_t i = 0; i < points.size(); ++i) {
            ASSERT_NEAR(moved[i].x, points[i].x, kRoundTripToleranceM / unitM)
                << c.source << " " << c.target;
            ASSERT_NEAR(moved[i].y, points[i].y, kRoundTripToleranceM / unitM)
                << c.source << " " << c.target;
            ASSERT_EQ(moved[i].z, points[i].z) << "z changed";
        }
    }
}

TEST(Reprojection, ThrowsCrsError_ForUnknownCrsAndUntransformablePoints) {
    EXPECT_THROW(crsFromUserInput("EPSG:999999", "--t_srs"), CrsError);
    EXPECT_THROW(crsFromUserInput("", "--t_srs"), CrsError);
    try {
        crsFromUserInput("not a crs", "--t_srs");
        FAIL();
    } catch (const CrsError& error) {
        EXPECT_NE(std::string(error.what()).find("--t_srs 'not a crs'"), std::string::npos);
    }
    const Reprojector toMercator(crsFromUserInput("EPSG:4326", "test"),
                                 crsFromUserInput("EPSG:3857", "test"));
    std::vector<Point3> beyondPole{{0.0, 1.0, 1.0}, {0.0, 95.0, 1.0}};
    try {
        toMercator.transform(beyondPole);
        FAIL() << "a latitude of 95 degrees was transformed";
    } catch (const CrsError& error) {
        EXPECT_NE(std::string(error.what()).find("1 of 2 points"), std::string::npos)
            << error.what();
    }
}

TEST(Crs, DescribesAndCompares) {
    const CrsDescription feet = describeCrs(crsFromUserInput("EPSG:2992", "test"));
    EXPECT_EQ(feet.code, "EPSG:2992");
    EXPECT_TRUE(feet.projected);
    EXPECT_NEAR(feet.metresPerUnit, 0.3048, 1e-12);
    EXPECT_TRUE(describeCrs(crsFromUserInput("EPSG:4326", "test")).geographic);
    EXPECT_TRUE(describeCrs("").name.empty());
    EXPECT_TRUE(sameCrs(crsFromUserInput("EPSG:32619", "a"), crsFromUserInput("EPSG:32619", "b")));
    EXPECT_FALSE(sameCrs(crsFromUserInput("EPSG:32619", "a"), crsFromUserInput("EPSG:32620", "b")));
    EXPECT_FALSE(sameCrs("", crsFromUserInput("EPSG:32619", "b")));
    EXPECT_TRUE(sameCrs("", ""));
    EXPECT_TRUE(describeCrs(geographicBaseCrs(crsFromUserInput("EPSG:32619", "a"))).geographic);
}

// The whole SRTM tile's reader points projected to UTM 19N: x, y where GeographicLib puts the
// cell centres (1 mm), z untouched, bit for bit.
TEST(Reprojection, ProjectsSrtmTileToUtm19_WithExactElevations) {
    const std::filesystem::path tile =
        std::filesystem::path(TERRATIN_SHARED_DEMS) / "srtmpy__N44W072" / "N44W072.hgt";
    if (!std::filesystem::exists(tile))
        GTEST_SKIP() << tile << " not available";
    const io::RasterPoints raster = io::readRasterPoints(tile.string(), {});
    const CrsDescription source = describeCrs(raster.crsWkt);
    ASSERT_TRUE(source.geographic);
    std::vector<Point3> centre;
    double lonSum = 0.0;
    double latSum = 0.0;
    for (const Point3& p : raster.points) {
        lonSum += p.x;
        latSum += p.y;
    }
    const auto n = static_cast<double>(raster.points.size());
    const UtmZone zone = standardUtmZone(lonSum / n, latSum / n);
    ASSERT_EQ(zone, (UtmZone{19, true}));
    const std::string target = utmZoneCrs(zone, raster.crsWkt);
    EXPECT_EQ(describeCrs(target).code, "EPSG:32619");

    std::vector<Point3> projected = raster.points;
    Reprojector(raster.crsWkt, target).transform(projected);
    for (std::size_t i = 0; i < projected.size(); ++i)
        ASSERT_EQ(projected[i].z, raster.points[i].z) << "elevation changed at point " << i;
    for (std::size_t i = 0; i < projected.size(); i += 997) {
        int z = 0;
        bool north = false;
        double x = 0.0;
        double y = 0.0;
        GeographicLib::UTMUPS::Forward(raster.points[i].y, raster.points[i].x, z, north, x, y, 19);
        ASSERT_NEAR(projected[i].x, x, kRoundTripToleranceM);
        ASSERT_NEAR(projected[i].y, y, kRoundTripToleranceM);
    }
}

} // namespace
} // namespace terratin::crs

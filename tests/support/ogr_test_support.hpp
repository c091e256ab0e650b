#pragma once
// Small OGR helpers for the writer tests (header-only: the core test support has no GDAL).

#include <cpl_conv.h>
#include <ogr_spatialref.h>

#include <gtest/gtest.h>

#include <string>

namespace terratin::test {

/// NAD83 / UTM zone 10N (EPSG:26910), Mt Hood's CRS, as OGR's WKT.
inline std::string utm10nWkt() {
    OGRSpatialReference srs;
    EXPECT_EQ(srs.importFromEPSG(26910), OGRERR_NONE);
    char* wkt = nullptr;
    EXPECT_EQ(srs.exportToWkt(&wkt), OGRERR_NONE);
    std::string result = wkt != nullptr ? wkt : "";
    CPLFree(wkt);
    return result;
}

} // namespace terratin::test

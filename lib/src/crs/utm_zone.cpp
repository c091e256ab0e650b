/// @file
/// Zone choice with GeographicLib, zone CRS with OGR.

#include "terratin/crs/utm_zone.hpp"

#include "../number_text.hpp"
#include "terratin/error.hpp"
#include "terratin/gdal_error.hpp"
#include "wkt.hpp"

#include <GeographicLib/UTMUPS.hpp>
#include <ogr_spatialref.h>

#include <cmath>

namespace terratin::crs {

using terratin::detail::numberText;

namespace {

constexpr std::string_view kStage = "CRS";
/// UPS parameters (NGA.SIG.0012, 2.0.0, "Universal Polar Stereographic"): scale at the pole.
constexpr double kUpsScale = 0.994;
constexpr double kUpsFalseOriginM = 2000000.0;

} // namespace

std::string UtmZone::name() const {
    if (zone == 0)
        return north ? "UPS North" : "UPS South";
    return "UTM zone " + std::to_string(zone) + (north ? "N" : "S");
}

UtmZone standardUtmZone(double longitudeDeg, double latitudeDeg) {
    if (!std::isfinite(longitudeDeg) || !std::isfinite(latitudeDeg) || latitudeDeg < -90.0 ||
        latitudeDeg > 90.0)
        throw CrsError(std::string(kStage) + ": no UTM/UPS zone for longitude " +
                       numberText(longitudeDeg) + ", latitude " + numberText(latitudeDeg) +
                       " (latitude outside -90..90 degrees: "
                       "is the input really geographic?)");
    UtmZone result;
    try {
        result.zone = GeographicLib::UTMUPS::StandardZone(latitudeDeg, longitudeDeg);
    } catch (const GeographicLib::GeographicErr& error) {
        throw CrsError(std::string(kStage) + ": GeographicLib: " + error.what());
    }
    result.north = latitudeDeg >= 0.0;
    return result;
}

std::string utmZoneCrs(const UtmZone& zone, const std::string& geographicWkt) {
    initialiseGdal();
    OGRSpatialReference base;
    if (!detail::importWkt(geographicWkt, base))
        throw CrsError(std::string(kStage) +
                       ": the CRS to choose a zone for cannot be read: " + lastGdalErrorMessage());
    OGRSpatialReference geographic;
    if (geographic.CopyGeogCSFrom(&base) != OGRERR_NONE)
        throw CrsError(std::string(kStage) + ": no geographic base CRS to put " + zone.name() +
                       " on: " + lastGdalErrorMessage());

    OGRSpatialReference wgs84;
    wgs84.importFromEPSG(4326);
    const char* const options[] = {"IGNORE_DATA_AXIS_TO_SRS_AXIS_MAPPING=YES",
                                   "CRITERION=EQUIVALENT_EXCEPT_AXIS_ORDER_GEOGCRS", nullptr};
    OGRSpatialReference projected;
    if (geographic.IsSame(&wgs84, options) != 0) {
        // WGS 84 / UTM zone nn N|S: EPSG 32600 + nn / 32700 + nn; UPS: 32661 / 32761.
        const int code = zone.zone == 0 ? (zone.north ? 32661 : 32761)
                                        : (zone.north ? 32600 : 32700) + zone.zone;
        if (projected.importFromEPSG(code) != OGRERR_NONE)
            throw CrsError(std::string(kStage) + ": EPSG:" + std::to_string(code) +
                           " is missing from PROJ's database: " + lastGdalErrorMessage());
    } else {
        projected.CopyGeogCSFrom(&geographic);
        const std::string name =
            std::string(geographic.GetName() ? geographic.GetName() : "") + " / " + zone.name();
        projected.SetProjCS(name.c_str());
        if (zone.zone == 0) {
            projected.SetPS(zone.north ? 90.0 : -90.0, 0.0, kUpsScale, kUpsFalseOriginM,
                            kUpsFalseOriginM);
        } else {
            projected.SetUTM(zone.zone, zone.north ? TRUE : FALSE);
        }
        projected.SetLinearUnits(SRS_UL_METER, 1.0);
    }
    std::string wkt = detail::exportWkt(projected);
    if (wkt.empty())
        throw CrsError(std::string(kStage) + ": cannot write " + zone.name() +
                       " as WKT: " + lastGdalErrorMessage());
    return wkt;
}

} // namespace terratin::crs

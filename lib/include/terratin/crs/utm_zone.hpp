#pragma once
/// @file
/// The UTM or UPS zone a geographic data set should be projected to, by GeographicLib's
/// UTMUPS::StandardZone (Karney, GeographicLib documentation, "UTMUPS": the standard zone,
/// with the Norway and Svalbard exceptions, and UPS beyond 84 N / 80 S).

#include <string>

namespace terratin::crs {

/// A UTM zone (1..60) or UPS (zone 0) and hemisphere.
struct UtmZone {
    /// 1..60 for UTM; 0 for UPS (polar stereographic).
    int zone = 0;
    bool north = true;

    /// "UTM zone 19N", "UPS North".
    [[nodiscard]] std::string name() const;
    friend bool operator==(const UtmZone&, const UtmZone&) = default;
};

/// The standard zone for a point at (longitude, latitude) in degrees.
/// Throws CrsError when latitude is outside [-90, 90] or either value is not finite.
UtmZone standardUtmZone(double longitudeDeg, double latitudeDeg);

/// The projected CRS of `zone` on the datum of `geographicWkt` (a geographic CRS, or a
/// projected one whose base is used): EPSG:326zz / 327zz / 32661 / 32761 when the datum is
/// WGS 84, else that datum's geographic CRS with a Transverse Mercator (UTM: scale 0.9996,
/// false easting 500 km, false northing 10 000 km south) or Polar Stereographic (UPS: scale
/// 0.994, false easting and northing 2 000 km) conversion, in metres. No datum shift ever
/// happens on the way. Returns WKT2. Throws CrsError when `geographicWkt` cannot be read.
std::string utmZoneCrs(const UtmZone& zone, const std::string& geographicWkt);

} // namespace terratin::crs

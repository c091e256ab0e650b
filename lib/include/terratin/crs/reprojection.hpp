#pragma once
/// @file
/// Coordinate reference systems: parsing what the user types, describing a CRS for reports, and
/// reprojecting points with PROJ (through OGRCoordinateTransformation).
///
/// Axis order: every coordinate terratin handles is in GDAL's traditional GIS order, x =
/// easting or longitude, y = northing or latitude, whatever order the CRS definition declares
/// (EPSG:4326 declares latitude first). Every CRS built here is used with
/// OAMS_TRADITIONAL_GIS_ORDER.

#include "terratin/geometry/point.hpp"

#include <memory>
#include <span>
#include <string>
#include <string_view>

namespace terratin::crs {

/// The CRS a user names: anything OGR's SetFromUserInput accepts ("EPSG:32619", "ESRI:102003",
/// WKT, PROJJSON, a PROJ string, "WGS84", a .prj file name). Returns it as WKT2:2019.
/// `option` (e.g. "--t_srs") appears in the message of the CrsError thrown when the text is not
/// a CRS, or is not horizontal: a vertical-only or geocentric CRS is refused; projected,
/// geographic (2D or 3D), engineering and compound CRSs with such a horizontal part pass.
std::string crsFromUserInput(const std::string& definition, std::string_view option);

/// What reports say about a CRS.
struct CrsDescription {
    /// "NAD83 / Oregon GIC Lambert (ft)"; empty for an empty WKT.
    std::string name;
    /// "EPSG:2992" when the CRS is (or is identified as) an EPSG entry, else empty.
    std::string code;
    /// Horizontal coordinates are angles (degrees) on an ellipsoid.
    bool geographic = false;
    /// Horizontal coordinates are projected (metres, feet...).
    bool projected = false;
    /// Name of the horizontal linear unit ("metre", "US survey foot"), empty when geographic.
    std::string linearUnit;
    /// Metres per horizontal linear unit (1 for metres, 0.3048 for feet), 0 when geographic.
    double metresPerUnit = 0.0;
};

/// Describes `wkt`; an empty WKT gives an empty description. Throws CrsError for a WKT that OGR
/// cannot read.
CrsDescription describeCrs(const std::string& wkt);

/// Whether two CRSs are the same (OGR's IsSame: same definition, names aside). Two empty WKTs
/// are the same; an empty and a non-empty one are not.
bool sameCrs(const std::string& wktA, const std::string& wktB);

/// The geographic CRS (datum, ellipsoid, degrees) underlying `wkt`, as WKT2.
/// Throws CrsError when `wkt` has none (an engineering CRS, say).
std::string geographicBaseCrs(const std::string& wkt);

/// Transforms horizontal coordinates from one CRS to another with PROJ. z is never touched:
/// terratin carries elevations through unchanged (see --z-factor for unit changes), so a TIN
/// built after reprojection holds the source elevations exactly.
/// Not thread-safe (PROJ contexts are per object): use one Reprojector per thread.
class Reprojector {
public:
    /// Throws CrsError when either WKT cannot be read or PROJ finds no transformation.
    Reprojector(const std::string& sourceWkt, const std::string& targetWkt);
    ~Reprojector();
    Reprojector(Reprojector&&) noexcept;
    Reprojector& operator=(Reprojector&&) noexcept;
    Reprojector(const Reprojector&) = delete;
    Reprojector& operator=(const Reprojector&) = delete;

    /// x, y of every point replaced by their image in the target CRS, z unchanged.
    /// Throws CrsError naming the first point PROJ could not transform (outside the
    /// projection's domain, say) and how many failed; on error the points are partly
    /// transformed. Complexity: O(n), in blocks of 64 Ki points.
    void transform(std::span<Point3> points) const;

    /// One point (x, y in the source CRS).
    [[nodiscard]] Point2 transform(Point2 point) const;

    /// The inverse direction: from target to source.
    [[nodiscard]] Reprojector inverse() const;

private:
    struct Impl;
    explicit Reprojector(std::unique_ptr<Impl> impl);
    std::unique_ptr<Impl> m_impl;
};

} // namespace terratin::crs

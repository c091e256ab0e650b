#pragma once
/// @file
/// GeoTIFF keys (as LAS stores them in its LASF_Projection VLRs 34735, 34736, 34737) to a CRS.
/// Internal to terratin::io.

#include <cstdint>
#include <span>
#include <string>
#include <string_view>

namespace terratin::io::detail {

/// The CRS that a GeoKeyDirectory (with its double and ASCII parameters) describes, as WKT2.
///
/// The keys are not interpreted here: they are wrapped into a minimal one-pixel TIFF in GDAL's
/// in-memory file system and read back with GDAL's GeoTIFF driver, so that every case libgeotiff
/// understands (EPSG codes, user-defined projections, units, vertical CRSs) is handled exactly
/// as GDAL handles a GeoTIFF. `stage` and `name` appear in messages.
/// Throws CrsError when the directory is malformed or GDAL finds no CRS in it.
std::string geoTiffKeysToWkt(std::span<const std::uint16_t> directory,
                             std::span<const double> doubleParams, std::string_view asciiParams,
                             std::string_view stage, std::string_view name);

/// `wkt` checked by OGR and exported as WKT2:2019 (WKT1 when WKT2 export fails).
/// Throws CrsError when OGR cannot import it.
std::string normaliseWkt(std::string_view wkt, std::string_view stage, std::string_view name);

} // namespace terratin::io::detail

#pragma once
/// @file
/// WKT export shared by the readers and the CRS module. Internal to terratin::io.

#include <string>

class OGRSpatialReference;

namespace terratin::crs::detail {

/// `srs` as WKT2:2019, or WKT1 when WKT2 export fails; empty when neither works.
std::string exportWkt(const OGRSpatialReference& srs);

/// A fresh OGRSpatialReference in traditional GIS axis order (x = easting / longitude) from
/// `wkt`; false when OGR cannot read it.
bool importWkt(const std::string& wkt, OGRSpatialReference& srs);

} // namespace terratin::crs::detail

#pragma once
/// @file
/// LandXmlWriter: a TinMesh as a LandXML 1.2 TIN surface for civil engineering software.
///
///   <LandXML version="1.2" date time>
///     <Units><Metric .../> or <Imperial .../></Units>     from the CRS's linear unit
///     <CoordinateSystem name epsgCode ogcWktCode/>         when there is a CRS
///     <Application name="terratin" version/>
///     <Surfaces><Surface name><Definition surfType="TIN" area2DSurf area3DSurf elevMax elevMin>
///       <Pnts><P id="1">northing easting elevation</P>...</Pnts>    ids 1..V, vertex order
///       <Faces><F>a b c</F>...</Faces>      point ids, counter-clockwise seen from above
///     </Definition></Surface></Surfaces>
///   </LandXML>
/// LandXML puts northing (y) before easting (x). Numbers are shortest round-trip decimals.

#include "mesh_writer.hpp"

#include <string>
#include <string_view>

namespace terratin::io::detail {

/// LandXML's row of the format table.
extern const MeshWriter kLandXmlWriter;

/// `text` with & < > " ' escaped for an XML attribute or element.
std::string xmlEscaped(std::string_view text);

} // namespace terratin::io::detail

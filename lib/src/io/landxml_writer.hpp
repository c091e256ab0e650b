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

#include "buffered_file.hpp"
#include "terratin/triangulate/tin_mesh.hpp"
#include "writer_support.hpp"

#include <algorithm>
#include <cstdint>
#include <limits>
#include <string>
#include <string_view>

namespace terratin::io::detail {

/// The Definition element's figures: the TIN's 2D and 3D areas (summed in triangle order) and
/// its elevations' range.
struct LandXmlSurface {
    double area2d = 0.0;
    double area3d = 0.0;
    double elevMin = std::numeric_limits<double>::infinity();
    double elevMax = -std::numeric_limits<double>::infinity();

    void addVertex(const Point3& p) {
        elevMin = std::min(elevMin, p.z);
        elevMax = std::max(elevMax, p.z);
    }
    void addTriangle(const Point3& a, const Point3& b, const Point3& c);
};

/// Everything before the first point (the header, the surface's Definition with `surface`'s
/// figures, "<Pnts>"); a point numbered `number` (from 0; its id is number + 1); what comes
/// between the points and the faces; a face of points a, b, c (numbered from 0); the end.
void putLandXmlHead(BufferedFile& file, const MeshFileInfo& info, const LandXmlSurface& surface);
void putLandXmlPoint(BufferedFile& file, std::uint64_t number, const Point3& p);
inline constexpr std::string_view kLandXmlBetween = "</Pnts>\n<Faces>\n";
void putLandXmlFace(BufferedFile& file, std::uint32_t a, std::uint32_t b, std::uint32_t c);
inline constexpr std::string_view kLandXmlEnd =
    "</Faces>\n</Definition>\n</Surface>\n</Surfaces>\n</LandXML>\n";

/// `text` with & < > " ' escaped for an XML attribute or element.
std::string xmlEscaped(std::string_view text);

/// Writes the whole file; returns vertices + triangles. Throws IoError, Cancelled.
std::uint64_t writeLandXml(const TinMesh& mesh, const MeshFileInfo& info, BufferedFile& file,
                           const ProgressTicker& ticker);

} // namespace terratin::io::detail

#pragma once
/// @file
/// OgrTinWriter: a TinMesh as Polygon Z triangles in a GeoPackage or an ESRI Shapefile.

#include "terratin/progress.hpp"
#include "terratin/triangulate/tin_mesh.hpp"

#include <filesystem>
#include <string>

namespace terratin::io {

/// Output vector formats.
enum class TinFormat { GeoPackage, Shapefile };

/// Parses "GPKG" / "SHP" (case-insensitive, also the GDAL driver names "GeoPackage" and
/// "ESRI Shapefile"); throws InvalidInputError for anything else.
TinFormat parseTinFormat(const std::string& name);

/// The format implied by the file extension (.gpkg, .shp); throws InvalidInputError when the
/// extension is not one of them.
TinFormat tinFormatFromPath(const std::filesystem::path& path);

/// How to write.
struct TinWriteOptions {
    TinFormat format = TinFormat::GeoPackage;
    /// Replace an existing output; without it an existing output is an error.
    bool overwrite = false;
    /// CRS of the vertices as WKT; empty writes no CRS.
    std::string crsWkt;
    /// Name of the triangle layer.
    std::string layerName = "tin";
};

/// Writes one Polygon Z feature per triangle (closed counter-clockwise ring, vertex z =
/// elevation) with the attributes z_min z_max z_mean slope_deg aspect_deg area_2d.
/// The data are written under a temporary name in the output's directory and renamed into
/// place only when complete: on any failure (or Cancelled) the temporary files are removed and
/// an existing output is left untouched. Throws IoError, InvalidInputError (existing output
/// without `overwrite`, empty mesh, a Shapefile past its 2 GB limits), CrsError (unusable
/// `crsWkt`), Cancelled. A GeoPackage without CRS is labelled "Undefined Cartesian SRS".
void writeTin(const TinMesh& mesh, const std::filesystem::path& output,
              const TinWriteOptions& options, const ProgressCallback& progress = {});

} // namespace terratin::io

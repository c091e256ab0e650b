#pragma once
/// @file
/// The output formats of a TIN, by name and by file extension.

#include "terratin/option_namer.hpp"

#include <filesystem>
#include <span>
#include <string>
#include <string_view>

namespace terratin::io {

/// Output formats. The first three are written through OGR as Polygon Z features; the others
/// are mesh formats written by terratin itself.
enum class TinFormat {
    GeoPackage, ///< .gpkg, OGR "GPKG"
    Shapefile,  ///< .shp, OGR "ESRI Shapefile"
    FlatGeobuf, ///< .fgb, OGR "FlatGeobuf"
    TwoDm,      ///< .2dm, SMS / MDAL 2D mesh (MESH2D, ND, E3T)
    Ply,        ///< .ply, binary little-endian Stanford PLY
    Obj,        ///< .obj, Wavefront OBJ with a local origin
    LandXml,    ///< .xml / .landxml, LandXML 1.2 TIN surface
};

/// Parses a format name, case-insensitive: gpkg (or GeoPackage), shp (or "ESRI Shapefile"),
/// fgb (or FlatGeobuf), 2dm, ply, obj, landxml (or xml).
/// Throws InvalidInputError, listing the accepted names, for anything else.
TinFormat parseTinFormat(const std::string& name);

/// The format implied by the file extension (.gpkg .shp .fgb .2dm .ply .obj .xml .landxml,
/// case-insensitive); throws InvalidInputError when the extension is none of them, pointing to
/// the format option as `optionName` names it ("format" by default).
TinFormat tinFormatFromPath(const std::filesystem::path& path, const OptionNamer& optionName = {});

/// A short display name: "GPKG", "ESRI Shapefile", "FlatGeobuf", "2DM", "PLY", "OBJ",
/// "LandXML" (the GDAL driver name for the OGR formats).
std::string_view tinFormatName(TinFormat format);

/// The file extension of a format, with its dot: ".gpkg", ".shp", ".fgb", ".2dm", ".ply",
/// ".obj", ".xml".
std::string_view tinFormatExtension(TinFormat format);

/// One output format as `terratin --formats` lists it.
struct TinFormatInfo {
    TinFormat format;
    /// The name --format takes first ("gpkg").
    std::string_view name;
    /// The extensions that select it, with their dots (".xml .landxml").
    std::string_view extensions;
    /// What a file of it holds, and what opens it.
    std::string_view carries;
};

/// Every output format, in the order of TinFormat.
std::span<const TinFormatInfo> tinFormats();

/// True for the formats written through OGR (GeoPackage, Shapefile, FlatGeobuf).
bool isOgrFormat(TinFormat format);

} // namespace terratin::io

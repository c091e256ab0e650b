#pragma once
/// @file
/// The output formats of a TIN, by name and by file extension.

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
/// the format option (marked, markOption).
TinFormat tinFormatFromPath(const std::filesystem::path& path);

/// A short display name: "GPKG", "ESRI Shapefile", "FlatGeobuf", "2DM", "PLY", "OBJ",
/// "LandXML" (the GDAL driver name for the OGR formats).
std::string_view tinFormatName(TinFormat format);

/// The file extension of a format, with its dot: ".gpkg", ".shp", ".fgb", ".2dm", ".ply",
/// ".obj", ".xml".
std::string_view tinFormatExtension(TinFormat format);

/// How a format holds a TIN.
enum class TinFormatKind {
    /// One Polygon Z feature per triangle, with attributes, written through OGR.
    Vector,
    /// Vertices and faces, written by terratin itself.
    Mesh,
};

/// One output format: the one row that says what the format is, for the parser, the writers'
/// checks, `terratin --formats` and the help.
struct TinFormatInfo {
    TinFormat format;
    /// The names --format takes, the first the usual one ("gpkg geopackage"), lower case.
    std::string_view names;
    /// The extensions that select it, with their dots, the first the one written (".xml
    /// .landxml").
    std::string_view extensions;
    /// What messages call it: GDAL's driver name for the vector formats ("GPKG").
    std::string_view displayName;
    /// The stage its writer's messages start with ("PlyWriter").
    std::string_view writerStage;
    TinFormatKind kind;
    /// Whether a file of it records the CRS.
    bool carriesCrs;
    /// Whether it takes the node and edge layers and --append-layer (GeoPackage alone).
    bool takesExtraLayers;
    /// Whether it can leave out its spatial index (the indexed vector formats).
    bool hasOptionalIndex;
    /// What a file of it holds, and what opens it.
    std::string_view carries;

    /// The first of `names`.
    [[nodiscard]] std::string_view name() const { return names.substr(0, names.find(' ')); }
    /// The first of `extensions`.
    [[nodiscard]] std::string_view extension() const {
        return extensions.substr(0, extensions.find(' '));
    }
};

/// Every output format, in the order of TinFormat.
std::span<const TinFormatInfo> tinFormats();

/// The row of `format`.
const TinFormatInfo& tinFormatInfo(TinFormat format);

/// "gpkg, shp, fgb, 2dm, ply, obj or landxml": every format's usual name, for messages.
std::string tinFormatNameList();

/// ".gpkg .shp .fgb .2dm .ply .obj .xml .landxml": every extension, for messages.
std::string tinFormatExtensionList();

/// True for the formats written through OGR (GeoPackage, Shapefile, FlatGeobuf).
bool isOgrFormat(TinFormat format);

} // namespace terratin::io

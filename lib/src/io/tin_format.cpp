#include "terratin/io/tin_format.hpp"

#include "terratin/error.hpp"
#include "terratin/text.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <utility>

namespace terratin::io {

namespace {

constexpr std::string_view kStage = "TinFormat";

constexpr std::array<std::pair<std::string_view, TinFormat>, 12> kNames = {{
    {"gpkg", TinFormat::GeoPackage},
    {"geopackage", TinFormat::GeoPackage},
    {"shp", TinFormat::Shapefile},
    {"esri shapefile", TinFormat::Shapefile},
    {"fgb", TinFormat::FlatGeobuf},
    {"flatgeobuf", TinFormat::FlatGeobuf},
    {"2dm", TinFormat::TwoDm},
    {"ply", TinFormat::Ply},
    {"obj", TinFormat::Obj},
    {"landxml", TinFormat::LandXml},
    {"xml", TinFormat::LandXml},
    {"mesh2d", TinFormat::TwoDm},
}};

constexpr std::array<std::pair<std::string_view, TinFormat>, 8> kExtensions = {{
    {".gpkg", TinFormat::GeoPackage},
    {".shp", TinFormat::Shapefile},
    {".fgb", TinFormat::FlatGeobuf},
    {".2dm", TinFormat::TwoDm},
    {".ply", TinFormat::Ply},
    {".obj", TinFormat::Obj},
    {".xml", TinFormat::LandXml},
    {".landxml", TinFormat::LandXml},
}};

constexpr std::array<TinFormatInfo, 7> kFormats = {{
    {TinFormat::GeoPackage, "gpkg", ".gpkg",
     "Polygon Z triangles with attributes, optional node and edge layers, R-tree, CRS; a QGIS "
     "vector layer; --append-layer adds layers to an existing file"},
    {TinFormat::Shapefile, "shp", ".shp",
     "Polygon Z triangles with attributes, CRS in .prj; 2 GB per component"},
    {TinFormat::FlatGeobuf, "fgb", ".fgb",
     "Polygon Z triangles with attributes, packed Hilbert R-tree, CRS"},
    {TinFormat::TwoDm, "2dm", ".2dm",
     "SMS 2D mesh: nodes and triangles, no CRS; a QGIS mesh layer"},
    {TinFormat::Ply, "ply", ".ply",
     "binary PLY mesh: vertices and faces, CRS as a comment; a QGIS mesh layer"},
    {TinFormat::Obj, "obj", ".obj",
     "Wavefront OBJ mesh about a local origin, no CRS; for 3D tools (QGIS does not open it)"},
    {TinFormat::LandXml, "landxml", ".xml .landxml",
     "LandXML 1.2 TIN surface with units, CRS and breaklines; for civil and CAD tools (QGIS "
     "does not open it)"},
}};

} // namespace

std::span<const TinFormatInfo> tinFormats() {
    return kFormats;
}

TinFormat parseTinFormat(const std::string& name) {
    const std::string lower = lowercase(name);
    for (const auto& [known, format] : kNames)
        if (lower == known)
            return format;
    throw InvalidInputError(std::string(kStage) + ": unknown output format '" + name +
                            "'; use gpkg, shp, fgb, 2dm, ply, obj or landxml");
}

TinFormat tinFormatFromPath(const std::filesystem::path& path, const OptionNamer& optionName) {
    const std::string extension = lowercase(path.extension().string());
    for (const auto& [known, format] : kExtensions)
        if (extension == known)
            return format;
    throw InvalidInputError(std::string(kStage) + ": cannot tell the output format of '" +
                            path.string() +
                            "' from its extension; use .gpkg .shp .fgb .2dm .ply .obj .xml (or " +
                            optionName("format") + ")");
}

std::string_view tinFormatName(TinFormat format) {
    switch (format) {
    case TinFormat::GeoPackage:
        return "GPKG";
    case TinFormat::Shapefile:
        return "ESRI Shapefile";
    case TinFormat::FlatGeobuf:
        return "FlatGeobuf";
    case TinFormat::TwoDm:
        return "2DM";
    case TinFormat::Ply:
        return "PLY";
    case TinFormat::Obj:
        return "OBJ";
    case TinFormat::LandXml:
        return "LandXML";
    }
    return "unknown";
}

std::string_view tinFormatExtension(TinFormat format) {
    switch (format) {
    case TinFormat::GeoPackage:
        return ".gpkg";
    case TinFormat::Shapefile:
        return ".shp";
    case TinFormat::FlatGeobuf:
        return ".fgb";
    case TinFormat::TwoDm:
        return ".2dm";
    case TinFormat::Ply:
        return ".ply";
    case TinFormat::Obj:
        return ".obj";
    case TinFormat::LandXml:
        return ".xml";
    }
    return "";
}

bool isOgrFormat(TinFormat format) {
    return format == TinFormat::GeoPackage || format == TinFormat::Shapefile ||
           format == TinFormat::FlatGeobuf;
}

} // namespace terratin::io

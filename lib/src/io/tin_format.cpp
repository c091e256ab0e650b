#include "terratin/io/tin_format.hpp"

#include "terratin/error.hpp"
#include "terratin/text.hpp"

#include <algorithm>
#include <array>

namespace terratin::io {

namespace {

constexpr std::string_view kStage = "TinFormat";

using Kind = TinFormatKind;

// The formats, in the order of TinFormat. Fields: format, names, extensions, display name,
// writer's stage, kind, CRS, node/edge layers and append, optional index, what it carries.
constexpr std::array<TinFormatInfo, 7> kFormats = {{
    {TinFormat::GeoPackage, "gpkg geopackage", ".gpkg", "GPKG", "OgrTinWriter", Kind::Vector, true,
     true, true,
     "Polygon Z triangles with attributes, optional node and edge layers, R-tree, CRS; a QGIS "
     "vector layer; --append-layer adds layers to an existing file"},
    {TinFormat::Shapefile, "shp esri_shapefile", ".shp", "ESRI Shapefile", "OgrTinWriter",
     Kind::Vector, true, false, false,
     "Polygon Z triangles with attributes, CRS in .prj; 2 GB per component"},
    {TinFormat::FlatGeobuf, "fgb flatgeobuf", ".fgb", "FlatGeobuf", "OgrTinWriter", Kind::Vector,
     true, false, true, "Polygon Z triangles with attributes, packed Hilbert R-tree, CRS"},
    {TinFormat::TwoDm, "2dm mesh2d", ".2dm", "2DM", "TwoDmWriter", Kind::Mesh, false, false, false,
     "SMS 2D mesh: nodes and triangles, no CRS; a QGIS mesh layer"},
    {TinFormat::Ply, "ply", ".ply", "PLY", "PlyWriter", Kind::Mesh, true, false, false,
     "binary PLY mesh: vertices and faces, CRS as a comment; a QGIS mesh layer"},
    {TinFormat::Obj, "obj", ".obj", "OBJ", "ObjWriter", Kind::Mesh, false, false, false,
     "Wavefront OBJ mesh about a local origin, no CRS; for 3D tools (QGIS does not open it)"},
    {TinFormat::LandXml, "landxml xml", ".xml .landxml", "LandXML", "LandXmlWriter", Kind::Mesh,
     true, false, false,
     "LandXML 1.2 TIN surface with units, CRS and breaklines; for civil and CAD tools (QGIS "
     "does not open it)"},
}};

/// Whether `word` is one of the space-separated `words`.
bool isOneOf(std::string_view word, std::string_view words) {
    while (!words.empty()) {
        const std::size_t end = std::min(words.find(' '), words.size());
        if (words.substr(0, end) == word)
            return true;
        words.remove_prefix(std::min(end + 1, words.size()));
    }
    return false;
}

} // namespace

std::span<const TinFormatInfo> tinFormats() {
    return kFormats;
}

const TinFormatInfo& tinFormatInfo(TinFormat format) {
    for (const TinFormatInfo& info : kFormats)
        if (info.format == format)
            return info;
    throw Error(std::string(kStage) + ": a format without a row in the table");
}

std::string tinFormatNameList() {
    std::string list;
    for (std::size_t i = 0; i < kFormats.size(); ++i) {
        if (i > 0)
            list += i + 1 == kFormats.size() ? " or " : ", ";
        list += kFormats[i].name();
    }
    return list;
}

std::string tinFormatExtensionList() {
    std::string list;
    for (const TinFormatInfo& info : kFormats) {
        if (!list.empty())
            list += ' ';
        list += info.extensions;
    }
    return list;
}

TinFormat parseTinFormat(const std::string& name) {
    // "ESRI Shapefile", GDAL's driver name, is spelt with an underscore in the table.
    std::string lower = lowercase(name);
    std::replace(lower.begin(), lower.end(), ' ', '_');
    for (const TinFormatInfo& info : kFormats)
        if (isOneOf(lower, info.names))
            return info.format;
    throw InvalidInputError(std::string(kStage) + ": unknown output format '" + name + "'; use " +
                            tinFormatNameList());
}

TinFormat tinFormatFromPath(const std::filesystem::path& path, const OptionNamer& optionName) {
    const std::string extension = lowercase(path.extension().string());
    for (const TinFormatInfo& info : kFormats)
        if (!extension.empty() && isOneOf(extension, info.extensions))
            return info.format;
    throw InvalidInputError(std::string(kStage) + ": cannot tell the output format of '" +
                            path.string() + "' from its extension; use " +
                            tinFormatExtensionList() + " (or " + optionName("format") + ")");
}

std::string_view tinFormatName(TinFormat format) {
    return tinFormatInfo(format).displayName;
}

std::string_view tinFormatExtension(TinFormat format) {
    return tinFormatInfo(format).extension();
}

bool isOgrFormat(TinFormat format) {
    return tinFormatInfo(format).kind == TinFormatKind::Vector;
}

} // namespace terratin::io

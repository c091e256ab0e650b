#include "terratin/io/tin_format.hpp"

#include "../text.hpp"
#include "landxml_writer.hpp"
#include "mesh_writer.hpp"
#include "obj_writer.hpp"
#include "ply_writer.hpp"
#include "terratin/error.hpp"
#include "two_dm_writer.hpp"

#include <algorithm>
#include <array>

namespace terratin::io {

using terratin::detail::lowercase;

namespace {

constexpr std::string_view kStage = "TinFormat";

using Kind = TinFormatKind;

/// A row of the format table: what a caller sees of the format, what messages that list
/// formats call it, and the writer of a mesh format (null for the vector formats, which OGR
/// writes).
struct FormatRow {
    TinFormatInfo info;
    std::string_view title;
    const detail::MeshWriter* meshWriter;
};

// The formats, in the order of TinFormat. Fields: format, names, extensions, display name,
// writer's stage, kind, CRS, node/edge layers and append, optional index, what it carries;
// then its title and the mesh format's writer.
constexpr std::array<FormatRow, 7> kRows = {{
    {{TinFormat::GeoPackage, "gpkg geopackage", ".gpkg", "GPKG", "OgrTinWriter", Kind::Vector, true,
      true, true,
      "Polygon Z triangles with attributes, optional node and edge layers, R-tree, CRS; a QGIS "
      "vector layer; --append-layer adds layers to an existing file"},
     "GeoPackage",
     nullptr},
    {{TinFormat::Shapefile, "shp esri_shapefile", ".shp", "ESRI Shapefile", "OgrTinWriter",
      Kind::Vector, true, false, false,
      "Polygon Z triangles with attributes, CRS in .prj; 2 GB per component"},
     "Shapefile",
     nullptr},
    {{TinFormat::FlatGeobuf, "fgb flatgeobuf", ".fgb", "FlatGeobuf", "OgrTinWriter", Kind::Vector,
      true, false, true, "Polygon Z triangles with attributes, packed Hilbert R-tree, CRS"},
     "FlatGeobuf",
     nullptr},
    {{TinFormat::TwoDm, "2dm mesh2d", ".2dm", "2DM", "TwoDmWriter", Kind::Mesh, false, false, false,
      "SMS 2D mesh: nodes and triangles, no CRS; a QGIS mesh layer"},
     "2DM",
     &detail::kTwoDmWriter},
    {{TinFormat::Ply, "ply", ".ply", "PLY", "PlyWriter", Kind::Mesh, true, false, false,
      "binary PLY mesh: vertices and faces, CRS as a comment; a QGIS mesh layer"},
     "PLY",
     &detail::kPlyWriter},
    {{TinFormat::Obj, "obj", ".obj", "OBJ", "ObjWriter", Kind::Mesh, false, false, false,
      "Wavefront OBJ mesh about a local origin, no CRS; for 3D tools (QGIS does not open it)"},
     "OBJ",
     &detail::kObjWriter},
    {{TinFormat::LandXml, "landxml xml", ".xml .landxml", "LandXML", "LandXmlWriter", Kind::Mesh,
      true, false, false,
      "LandXML 1.2 TIN surface with units, CRS and breaklines; for civil and CAD tools (QGIS "
      "does not open it)"},
     "LandXML",
     &detail::kLandXmlWriter},
}};

/// The rows as callers see them (tinFormats).
constexpr std::array<TinFormatInfo, kRows.size()> publicRows() {
    std::array<TinFormatInfo, kRows.size()> infos{};
    for (std::size_t i = 0; i < kRows.size(); ++i)
        infos[i] = kRows[i].info;
    return infos;
}

constexpr std::array<TinFormatInfo, kRows.size()> kFormats = publicRows();

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

TinFormat tinFormatFromPath(const std::filesystem::path& path) {
    const std::string extension = lowercase(path.extension().string());
    for (const TinFormatInfo& info : kFormats)
        if (!extension.empty() && isOneOf(extension, info.extensions))
            return info.format;
    throw InvalidInputError(std::string(kStage) + ": cannot tell the output format of '" +
                            path.string() + "' from its extension; use " +
                            tinFormatExtensionList() + " (or " + markOption("format") + ")");
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

std::string_view detail::formatTitle(TinFormat format) {
    for (const FormatRow& row : kRows)
        if (row.info.format == format)
            return row.title;
    throw Error(std::string(kStage) + ": a format without a row in the table");
}

const detail::MeshWriter& detail::meshWriterOf(TinFormat format) {
    for (const FormatRow& row : kRows)
        if (row.info.format == format && row.meshWriter != nullptr)
            return *row.meshWriter;
    throw InvalidInputError(std::string(tinFormatName(format)) + " is not a mesh format");
}

} // namespace terratin::io

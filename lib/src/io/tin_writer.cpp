/// @file
/// writeTin: checks everything that can be refused before the first byte is written, then
/// hands the mesh to the writer of its format (OGR for the vector formats, terratin's own
/// buffered writers for the mesh formats), and writes the optional QGIS style beside it.

#include "terratin/io/tin_writer.hpp"

#include "atomic_output.hpp"
#include "buffered_file.hpp"
#include "mesh_writer.hpp"
#include "ogr_tin_writer.hpp"
#include "ogr_triangle_layer.hpp"
#include "style_beside.hpp"
#include "terratin/error.hpp"
#include "terratin/gdal_error.hpp"
#include "writer_support.hpp"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <memory>
#include <optional>
#include <string_view>
#include <system_error>
#include <vector>

namespace terratin::io {

namespace fs = std::filesystem;

namespace {

constexpr std::string_view kStage = "TinWriter";

/// Share of the progress range for the mesh writers' records; the rest is flushing and the
/// rename.
constexpr double kMeshRecordShare = 0.98;

[[noreturn]] void throwInvalid(std::string_view stage, const std::string& message) {
    throw InvalidInputError(std::string(stage) + ": " + message);
}

void checkMesh(std::string_view stage, const TinMesh& mesh, const fs::path& output,
               const TinWriteOptions& options) {
    const std::string nothing = "; nothing written to " + detail::quoted(output);
    if (mesh.triangles.size() % 3 != 0)
        throwInvalid(stage, "the mesh's triangle array has " +
                                std::to_string(mesh.triangles.size()) +
                                " entries, not a multiple of 3" + nothing);
    if (mesh.triangleCount() == 0)
        throwInvalid(stage, "the mesh has no triangles" + nothing);
    const std::size_t vertexCount = mesh.vertexCount();
    for (std::size_t i = 0; i < mesh.triangles.size(); ++i) {
        if (mesh.triangles[i] >= vertexCount)
            throwInvalid(stage, "triangle " + std::to_string(i / 3) + " refers to vertex " +
                                    std::to_string(mesh.triangles[i]) + " of " +
                                    std::to_string(vertexCount) + nothing);
    }
    if (options.edges && mesh.neighbours.size() != mesh.triangles.size())
        throwInvalid(stage, "the mesh has no neighbour array, needed for the edge layer" + nothing);
    if (!options.vertexCells.empty() && options.vertexCells.size() != vertexCount)
        throwInvalid(stage, "vertexCells has " + std::to_string(options.vertexCells.size()) +
                                " entries for " + std::to_string(vertexCount) + " vertices" +
                                nothing);
    if (!options.constrainedEdges.empty() &&
        options.constrainedEdges.size() != mesh.triangles.size())
        throwInvalid(stage, "constrainedEdges has " +
                                std::to_string(options.constrainedEdges.size()) + " entries for " +
                                std::to_string(mesh.triangles.size()) + " half-edges" + nothing);
}

detail::MeshFileInfo meshFileInfo(std::string_view stage, const TinWriteOptions& options) {
    detail::MeshFileInfo info;
    info.name = options.layerName;
    info.crs = detail::summariseCrs(stage, options.crsWkt);
    info.softwareVersion = options.softwareVersion;
    info.breaklines = &options.breaklines;
    return info;
}

TinWriteResult writeMeshFormat(const TinMesh& mesh, const fs::path& output,
                               const TinWriteOptions& options, const detail::MeshFileInfo& info,
                               const ProgressCallback& progress) {
    const std::string_view stage = detail::writerStage(options.format);
    const detail::AtomicOutput temporaries(stage, output,
                                           detail::existingTargetFor(options.overwrite));
    const fs::path temporary = temporaries.temporary(output.extension().string());
    const std::uint64_t total = mesh.vertexCount() + mesh.triangleCount();
    const detail::ProgressTicker ticker(stage, progress, output, 0.0, kMeshRecordShare, total);
    std::uint64_t written = 0;
    {
        detail::BufferedFile file(stage, temporary, output);
        written = detail::meshWriterOf(options.format).writeWhole(mesh, info, file, ticker);
        // The last chance to cancel: nothing is in place before it.
        ticker.report(total, "Finishing");
        file.close();
    }
    temporaries.commit(temporary, output);
    return {written};
}

/// Every file a write of `output` puts in place (a Shapefile's components and sidecars, the
/// style).
std::vector<fs::path> outputFiles(const fs::path& output, const TinWriteOptions& options) {
    std::vector<fs::path> outputs = isOgrFormat(options.format)
                                        ? detail::ogrOutputFiles(output, options.format)
                                        : std::vector<fs::path>{output};
    if (options.qgisStyle)
        outputs.push_back(detail::stylePath(output));
    return outputs;
}

/// The character of `text` that starts at byte `at`, and `at` moved past it; nullopt (and `at`
/// left) when the bytes there are not one well-formed UTF-8 character (RFC 3629: the shortest
/// form, no UTF-16 surrogate, nothing past U+10FFFF).
std::optional<char32_t> nextUtf8Character(std::string_view text, std::size_t& at) {
    const auto byte = [&](std::size_t i) { return static_cast<unsigned char>(text[i]); };
    const unsigned char lead = byte(at);
    if (lead < 0x80) {
        ++at;
        return lead;
    }
    // The length a lead byte announces, and the range its second byte must fall in: narrower
    // than 0x80..0xBF after E0 and F0 (overlong forms), ED (surrogates) and F4 (past U+10FFFF).
    std::size_t length = 0;
    unsigned char low = 0x80;
    unsigned char high = 0xBF;
    if (lead >= 0xC2 && lead <= 0xDF) {
        length = 2;
    } else if (lead >= 0xE0 && lead <= 0xEF) {
        length = 3;
        low = lead == 0xE0 ? 0xA0 : 0x80;
        high = lead == 0xED ? 0x9F : 0xBF;
    } else if (lead >= 0xF0 && lead <= 0xF4) {
        length = 4;
        low = lead == 0xF0 ? 0x90 : 0x80;
        high = lead == 0xF4 ? 0x8F : 0xBF;
    } else {
        return std::nullopt; // a continuation byte, 0xC0 or 0xC1 (overlong), or 0xF5..0xFF
    }
    if (at + length > text.size() || byte(at + 1) < low || byte(at + 1) > high)
        return std::nullopt;
    char32_t character = lead & (0xFFU >> (length + 1));
    for (std::size_t i = 1; i < length; ++i) {
        if ((byte(at + i) & 0xC0U) != 0x80U)
            return std::nullopt;
        character = (character << 6U) | (byte(at + i) & 0x3FU);
    }
    at += length;
    return character;
}

/// Which formats take which options, by the flags of their rows in the format table.
bool takesExtraLayers(const TinFormatInfo& format) {
    return format.takesExtraLayers;
}
bool hasOptionalIndex(const TinFormatInfo& format) {
    return format.hasOptionalIndex;
}
/// The QGIS style is a vector layer's.
bool takesStyle(const TinFormatInfo& format) {
    return format.kind == TinFormatKind::Vector;
}

/// The titles of the formats that `take`, for a message: "GeoPackage and FlatGeobuf",
/// "GeoPackage, Shapefile and FlatGeobuf" (with `last` " and ").
std::string formatsThat(bool (*take)(const TinFormatInfo&), std::string_view last = " and ") {
    std::vector<std::string_view> titles;
    for (const TinFormatInfo& info : tinFormats())
        if (take(info))
            titles.push_back(detail::formatTitle(info.format));
    std::string list;
    for (std::size_t i = 0; i < titles.size(); ++i) {
        if (i > 0)
            list += i + 1 == titles.size() ? last : ", ";
        list += titles[i];
    }
    return list;
}

/// "a GeoPackage output (.gpkg)": the formats that take the node and edge layers.
std::string extraLayerOutput() {
    std::string extensions;
    for (const TinFormatInfo& info : tinFormats())
        if (takesExtraLayers(info))
            extensions += (extensions.empty() ? "" : " or ") + std::string(info.extension());
    return "a " + formatsThat(takesExtraLayers, " or ") + " output (" + extensions + ")";
}

/// What the options ask of the output format `row`.
void checkOptionsOfFormat(const TinWriteOptions& options, const TinFormatInfo& row) {
    const std::string format(row.displayName);
    const std::string needsGeoPackage = " needs " + extraLayerOutput() + ", not " + format;
    if (options.nodes && !takesExtraLayers(row))
        throwInvalid(kStage, markOption("nodes") + needsGeoPackage);
    if (options.edges && !takesExtraLayers(row))
        throwInvalid(kStage, markOption("edges") + needsGeoPackage);
    if (options.appendLayer && !takesExtraLayers(row))
        throwInvalid(kStage, markOption("append_layer") + needsGeoPackage);
    if (!options.spatialIndex && !hasOptionalIndex(row))
        throwInvalid(kStage, markOption("no_spatial_index") + " applies to " +
                                 formatsThat(hasOptionalIndex) + ", not " + format);
    if (options.qgisStyle && !takesStyle(row))
        throwInvalid(kStage, markOption("qgis_style") + " applies to " + formatsThat(takesStyle) +
                                 " outputs, not " + format);
    if (options.qgisStyle && options.attributes == AttributeSet::None)
        throwInvalid(kStage, markOption("qgis_style") + " colours by z_mean: it needs " +
                                 markOption("attributes") + " basic or all");
}

/// Refuses a layer name that holds a control character, is not UTF-8, or holds U+FFFE or
/// U+FFFF.
void checkLayerNameText(const std::string& layerName) {
    // The mesh formats write the name raw into a line of text (2DM MESHNAME, OBJ "o"): a
    // newline in it starts a record of its own and shifts every index after it. No format has
    // a use for control characters in a name, so every one refuses them.
    const auto control = std::find_if(layerName.begin(), layerName.end(),
                                      [](unsigned char ch) { return ch < 0x20 || ch == 0x7F; });
    if (control != layerName.end()) {
        char code[8];
        std::snprintf(code, sizeof code, "0x%02X", static_cast<unsigned char>(*control));
        throwInvalid(kStage, "the layer name holds a control character (" + std::string(code) +
                                 " at byte " + std::to_string(control - layerName.begin() + 1) +
                                 "); use printable characters only");
    }
    // A GeoPackage table name is UTF-8 text to SQLite and to every reader, and LandXML says
    // encoding="UTF-8": other bytes (Latin-1 from a script, a name cut mid-character) make an
    // unreadable table name and XML that is not well-formed. U+FFFE and U+FFFF are UTF-8 but
    // no characters, and XML 1.0 cannot hold them.
    for (std::size_t at = 0; at < layerName.size();) {
        const std::size_t start = at;
        const std::optional<char32_t> character = nextUtf8Character(layerName, at);
        char code[16];
        if (!character) {
            std::snprintf(code, sizeof code, "0x%02X",
                          static_cast<unsigned char>(layerName[start]));
            throwInvalid(kStage, "the layer name is not valid UTF-8 (" + std::string(code) +
                                     " at byte " + std::to_string(start + 1) +
                                     "); give it in UTF-8");
        }
        if (*character == 0xFFFE || *character == 0xFFFF) {
            std::snprintf(code, sizeof code, "U+%04X", static_cast<unsigned>(*character));
            throwInvalid(kStage, "the layer name holds " + std::string(code) + " at byte " +
                                     std::to_string(start + 1) +
                                     ", which is no character; use printable characters only");
        }
    }
}

/// The layer name: the name of a table beside others in a format of several layers, so not
/// empty and not the node or edge layer's, and text every format can hold.
void checkLayerName(const TinWriteOptions& options, const TinFormatInfo& row) {
    if (takesExtraLayers(row) && options.layerName.empty())
        throwInvalid(kStage, "the layer name is empty");
    checkLayerNameText(options.layerName);
    if (takesExtraLayers(row) && (options.nodes || options.edges) &&
        (nodeLayerName(options.layerName) == options.layerName ||
         edgeLayerName(options.layerName) == options.layerName))
        throwInvalid(kStage, "the layer name '" + options.layerName +
                                 "' collides with the node or edge layer");
}

} // namespace

std::string nodeLayerName(const std::string& layerName) {
    return layerName == "tin" ? std::string("nodes") : layerName + "_nodes";
}

std::string edgeLayerName(const std::string& layerName) {
    return layerName == "tin" ? std::string("edges") : layerName + "_edges";
}

void checkTinWriteOptions(const TinWriteOptions& options) {
    const TinFormatInfo& format = tinFormatInfo(options.format);
    checkOptionsOfFormat(options, format);
    checkLayerName(options, format);
}

void checkTinOutput(const fs::path& output, const TinWriteOptions& options) {
    const std::string_view stage = detail::writerStage(options.format);
    detail::checkOutputLocation(stage, output);
    std::vector<fs::path> outputs = outputFiles(output, options);
    // Not even --overwrite replaces a device, a FIFO or a symbolic link.
    detail::refuseIrregularOutputs(stage, outputs);
    // Appending to an existing GeoPackage is what --append-layer asks for; its layers are
    // checked when the copy is opened.
    if (options.appendLayer)
        outputs.erase(outputs.begin());
    detail::refuseExistingOutputs(stage, outputs, options.overwrite);
}

TinWriteResult writeTin(const TinMesh& mesh, const fs::path& output, const TinWriteOptions& options,
                        const ProgressCallback& progress) {
    initialiseGdal();
    const std::string_view stage = detail::writerStage(options.format);

    // Everything that can be refused is refused before the first byte is written.
    checkTinWriteOptions(options);
    checkMesh(stage, mesh, output, options);
    if (options.format == TinFormat::Shapefile)
        detail::checkShapefileLimits(mesh.triangleCount(), options.attributes, output);
    std::optional<detail::MeshFileInfo> meshInfo;
    if (!isOgrFormat(options.format))
        meshInfo = meshFileInfo(stage, options); // validates the CRS
    checkTinOutput(output, options);
    // The style goes to its temporary first and is renamed after the data, so a failure in
    // either leaves both old files in place.
    std::optional<detail::StyleBeside> style;
    if (options.qgisStyle) {
        const auto [lowest, highest] =
            std::minmax_element(mesh.vertices.begin(), mesh.vertices.end(),
                                [](const Point3& a, const Point3& b) { return a.z < b.z; });
        style.emplace(stage, output, outputFiles(output, options), options);
        style->write(lowest->z, highest->z);
    }

    const TinWriteResult result = isOgrFormat(options.format)
                                      ? detail::writeOgrTin(mesh, output, options, progress)
                                      : writeMeshFormat(mesh, output, options, *meshInfo, progress);
    if (style)
        style->commit();

    // The output is complete and in place: there is nothing left to cancel.
    if (progress)
        progress(1.0, "Done");
    return result;
}

} // namespace terratin::io

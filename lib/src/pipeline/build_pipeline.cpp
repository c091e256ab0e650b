#include "terratin/pipeline/build_pipeline.hpp"

#include "terratin/error.hpp"
#include "terratin/io/gdal_error.hpp"
#include "terratin/io/raster_reader.hpp"
#include "terratin/triangulate/mesh_validation.hpp"
#include "terratin/triangulate/triangulate.hpp"

#include <ogr_spatialref.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <sstream>

namespace terratin {

namespace {

// Share of the whole run each phase gets on the progress bar, roughly their usual cost.
constexpr double kReadShare = 0.1;
constexpr double kTriangulateShare = 0.4;
constexpr double kWriteShare = 0.5;

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point start) {
    return std::chrono::duration<double>(Clock::now() - start).count();
}

// Maps a phase's own 0..1 progress onto [start, start + share] of the whole run.
ProgressCallback phaseProgress(const ProgressCallback& progress, double start, double share) {
    if (!progress)
        return {};
    return [progress, start, share](double fraction, std::string_view message) {
        return progress(start + share * fraction, message);
    };
}

void checkOutputPath(const BuildOptions& options) {
    namespace fs = std::filesystem;
    std::error_code error;
    if (fs::exists(options.output, error) && !options.overwrite && !options.appendLayer)
        throw InvalidInputError("Output: '" + options.output.string() +
                                "' already exists; use --overwrite to replace it");
    const fs::path directory =
        options.output.has_parent_path() ? options.output.parent_path() : fs::path(".");
    if (!fs::is_directory(directory, error))
        throw IoError("Output: directory '" + directory.string() + "' does not exist");
}

void describeCrs(const std::string& wkt, BuildReport& report) {
    if (wkt.empty())
        return;
    OGRSpatialReference srs;
    if (srs.importFromWkt(wkt.c_str()) != OGRERR_NONE)
        return; // the writer will report an unusable CRS with context
    if (const char* name = srs.GetName())
        report.crsName = name;
    srs.AutoIdentifyEPSG();
    const char* authority = srs.GetAuthorityName(nullptr);
    const char* code = srs.GetAuthorityCode(nullptr);
    if (authority != nullptr && code != nullptr)
        report.crsCode = std::string(authority) + ":" + code;
}

std::string formatName(io::TinFormat format) { return std::string(io::tinFormatName(format)); }

// The raster cell of every vertex, for the GeoPackage nodes layer.
std::vector<io::RasterCell> vertexCells(const TinMesh& mesh, const io::RasterPoints& raster) {
    std::vector<io::RasterCell> cells(mesh.vertexCount());
    const auto width = static_cast<std::uint64_t>(raster.width);
    for (std::size_t v = 0; v < cells.size(); ++v) {
        const std::uint64_t cell = raster.cellIndex[mesh.sourceIndex[v]];
        cells[v] = {static_cast<std::int64_t>(cell / width),
                    static_cast<std::int64_t>(cell % width)};
    }
    return cells;
}

std::string jsonString(const std::string& text) {
    std::string quoted = "\"";
    for (const char c : text) {
        switch (c) {
        case '"':
            quoted += "\\\"";
            break;
        case '\\':
            quoted += "\\\\";
            break;
        case '\n':
            quoted += "\\n";
            break;
        case '\t':
            quoted += "\\t";
            break;
        default:
            if (static_cast<unsigned char>(c) < 0x20) {
                char escaped[8];
                std::snprintf(escaped, sizeof escaped, "\\u%04x", static_cast<unsigned>(c));
                quoted += escaped;
            } else {
                quoted += c;
            }
        }
    }
    return quoted + "\"";
}

} // namespace

BuildReport runBuild(const BuildOptions& options, const ProgressCallback& progress) {
    const Clock::time_point start = Clock::now();
    const io::TinFormat format = options.format ? *options.format
                                                : io::tinFormatFromPath(options.output);
    io::TinWriteOptions writeOptions;
    writeOptions.format = format;
    writeOptions.overwrite = options.overwrite;
    writeOptions.layerName = options.layerName;
    writeOptions.attributes = options.attributes;
    writeOptions.nodes = options.nodes;
    writeOptions.edges = options.edges;
    writeOptions.appendLayer = options.appendLayer;
    writeOptions.spatialIndex = options.spatialIndex;
    writeOptions.qgisStyle = options.qgisStyle;
    io::checkTinWriteOptions(writeOptions); // contradictory options fail before reading
    checkOutputPath(options);

    BuildReport report;
    report.input = options.input;
    report.output = options.output.string();
    report.format = formatName(format);

    Clock::time_point phase = Clock::now();
    io::RasterReadOptions readOptions;
    readOptions.band = options.band;
    io::RasterPoints raster =
        io::readRasterPoints(options.input, readOptions, phaseProgress(progress, 0.0, kReadShare));
    report.rasterCells = static_cast<std::uint64_t>(raster.width) *
                         static_cast<std::uint64_t>(raster.height);
    report.skippedCells = raster.skippedCells;
    report.points = raster.points.size();
    describeCrs(raster.crsWkt, report);
    report.timings.read = secondsSince(phase);

    phase = Clock::now();
    const TriangulationResult triangulation =
        triangulate(raster.points, options.triangulation,
                    phaseProgress(progress, kReadShare, kTriangulateShare));
    raster.points = {}; // the mesh holds its own copy of the vertices
    report.duplicates = triangulation.duplicatePoints;
    report.vertices = triangulation.mesh.vertexCount();
    report.triangles = triangulation.mesh.triangleCount();
    report.method = toString(triangulation.method);
    report.threads = triangulation.threads;
    report.historyBytesPerPoint = static_cast<double>(triangulation.historyBytes) /
                                  static_cast<double>(std::max<std::uint64_t>(report.points, 1));
    report.timings.triangulate = secondsSince(phase);

    if (options.validate) {
        phase = Clock::now();
        const MeshValidation validation = validateDelaunay(triangulation.mesh);
        if (!validation.ok())
            throw Error("Validation: the mesh is not an exact Delaunay triangulation: " +
                        (validation.problems.empty() ? std::string("unknown problem")
                                                     : validation.problems.front()));
        report.validated = true;
        report.timings.validate = secondsSince(phase);
    }

    phase = Clock::now();
    writeOptions.crsWkt = raster.crsWkt;
    if (options.nodes)
        writeOptions.vertexCells = vertexCells(triangulation.mesh, raster);
    const io::TinWriteResult written =
        io::writeTin(triangulation.mesh, options.output, writeOptions,
                     phaseProgress(progress, kReadShare + kTriangulateShare, kWriteShare));
    report.timings.write = secondsSince(phase);
    report.writeFeatures = written.features;
    report.writeFeaturesPerSecond =
        report.timings.write > 0.0
            ? static_cast<double>(written.features) / report.timings.write
            : 0.0;
    report.timings.total = secondsSince(start);
    if (progress)
        progress(1.0, "done");
    return report;
}

std::string toJson(const BuildReport& report) {
    std::ostringstream json;
    json.precision(6);
    json << std::fixed;
    json << "{\"input\": " << jsonString(report.input)
         << ", \"output\": " << jsonString(report.output)
         << ", \"format\": " << jsonString(report.format)
         << ", \"crs\": {\"name\": " << jsonString(report.crsName)
         << ", \"code\": " << jsonString(report.crsCode) << "}"
         << ", \"counts\": {\"raster_cells\": " << report.rasterCells
         << ", \"skipped_cells\": " << report.skippedCells << ", \"points\": " << report.points
         << ", \"duplicates\": " << report.duplicates << ", \"vertices\": " << report.vertices
         << ", \"triangles\": " << report.triangles << "}"
         << ", \"triangulation\": {\"method\": " << jsonString(report.method)
         << ", \"threads\": " << report.threads
         << ", \"history_bytes_per_point\": " << report.historyBytesPerPoint << "}"
         << ", \"timings\": {\"read\": " << report.timings.read
         << ", \"triangulate\": " << report.timings.triangulate
         << ", \"validate\": " << report.timings.validate
         << ", \"write\": " << report.timings.write << ", \"total\": " << report.timings.total
         << "}, \"validated\": " << (report.validated ? "true" : "false")
         << ", \"writing\": {\"features\": " << report.writeFeatures
         << ", \"features_per_second\": " << report.writeFeaturesPerSecond << "}}";
    return json.str();
}

std::string toSummaryLine(const BuildReport& report) {
    char line[512];
    std::snprintf(line, sizeof line,
                  "%llu points (%llu duplicates, %llu nodata cells skipped) -> %llu triangles; "
                  "read %.2f s, triangulate %.2f s, write %.2f s (%.0f features/s), total %.2f s",
                  static_cast<unsigned long long>(report.points),
                  static_cast<unsigned long long>(report.duplicates),
                  static_cast<unsigned long long>(report.skippedCells),
                  static_cast<unsigned long long>(report.triangles), report.timings.read,
                  report.timings.triangulate, report.timings.write,
                  report.writeFeaturesPerSecond, report.timings.total);
    return line;
}

} // namespace terratin

#pragma once
/// @file
/// `terratin build` as a library call: read -> triangulate -> write, timed and reported.
/// The CLI only maps its arguments onto BuildOptions and prints the BuildReport.

#include "terratin/io/tin_writer.hpp"
#include "terratin/progress.hpp"
#include "terratin/triangulate/triangulate.hpp"

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>

namespace terratin {

/// Everything `terratin build` can be asked.
struct BuildOptions {
    /// A raster GDAL can open.
    std::string input;
    std::filesystem::path output;
    /// Output format; when unset it follows the output's extension (.gpkg .shp .fgb .2dm .ply
    /// .obj .xml .landxml).
    std::optional<io::TinFormat> format;
    /// 1-based raster band.
    int band = 1;
    bool overwrite = false;
    /// Seed, method, threads, duplicate policy... of the triangulation.
    TriangulationOptions triangulation;
    /// Check the mesh with validateDelaunay before writing; a failure is an error.
    bool validate = false;
    /// Name of the triangle layer in the output.
    std::string layerName = "tin";
    /// Triangle attribute columns of the vector formats.
    io::AttributeSet attributes = io::AttributeSet::All;
    /// GeoPackage: also a nodes layer (with the source raster row / col) and an edges layer.
    bool nodes = false;
    bool edges = false;
    /// GeoPackage: add the layers to an existing GeoPackage (other layers untouched).
    bool appendLayer = false;
    /// GeoPackage / FlatGeobuf: build the spatial index (the slow part of a GeoPackage).
    bool spatialIndex = true;
    /// Vector formats: write a QGIS .qml style beside the output.
    bool qgisStyle = false;
};

/// Wall-clock seconds per phase.
struct BuildTimings {
    double read = 0.0;
    double triangulate = 0.0;
    double validate = 0.0;
    double write = 0.0;
    double total = 0.0;
};

/// What a build did.
struct BuildReport {
    std::string input;
    std::string output;
    std::string format;
    /// CRS name (e.g. "NAD83 / UTM zone 10N"), empty when the input has none.
    std::string crsName;
    /// "EPSG:26910" when the CRS has an EPSG code, else empty.
    std::string crsCode;
    std::uint64_t rasterCells = 0;
    std::uint64_t skippedCells = 0;
    std::uint64_t points = 0;
    std::uint64_t duplicates = 0;
    std::uint64_t vertices = 0;
    std::uint64_t triangles = 0;
    /// The triangulation method that ran and its threads in all.
    std::string method;
    unsigned threads = 1;
    /// Bytes of point-location history per input point.
    double historyBytesPerPoint = 0.0;
    bool validated = false;
    BuildTimings timings;
    /// Features (vector formats, all layers) or records (mesh formats: vertices + faces)
    /// written, and their rate over the write phase.
    std::uint64_t writeFeatures = 0;
    double writeFeaturesPerSecond = 0.0;
};

/// Runs the build. Before reading anything it refuses an existing output without
/// `overwrite` (InvalidInputError) and a missing output directory (IoError); every error is a
/// terratin::Error whose message names the stage; the output is written atomically (see
/// io::writeTin). `progress` receives the fraction of the whole build (reading 10 %,
/// triangulating 40 %, writing 50 %).
BuildReport runBuild(const BuildOptions& options, const ProgressCallback& progress = {});

/// The report as one JSON object: input, output, format, crs {name, code}, counts {...},
/// triangulation {method, threads, history_bytes_per_point}, timings {read, triangulate,
/// validate, write, total} in seconds, validated, writing {features, features_per_second}.
std::string toJson(const BuildReport& report);

/// One human-readable line: points, duplicates, triangles and seconds per phase.
std::string toSummaryLine(const BuildReport& report);

} // namespace terratin

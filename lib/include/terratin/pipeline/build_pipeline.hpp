#pragma once
/// @file
/// `terratin build` as a library call: read -> triangulate -> write, timed and reported.
/// The CLI only maps its arguments onto BuildOptions and prints the BuildReport.

#include "terratin/io/tin_writer.hpp"
#include "terratin/progress.hpp"
#include "terratin/refine/refine.hpp"
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
    /// Output format; when unset it follows the output's extension (.gpkg, .shp).
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
    /// Terrain simplification (--max-error, --max-points, --max-triangles, --max-hole,
    /// --fill-holes): when set, the raster is read as a HeightGrid and refined instead of
    /// triangulating every valid cell; `refine->threads` 0 follows triangulation.threads and
    /// `validate` above applies to the refined TIN before its holes are cut.
    std::optional<RefineOptions> refine;
    /// Drop the triangles with an edge longer than this (planimetric, CRS units) from the final
    /// TIN, whatever built it (meant for point clouds, whose hull bridges gaps).
    std::optional<double> maxEdge;
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
    /// Set when BuildOptions::refine was: what the refinement achieved, measured over every
    /// valid cell after the build (z units).
    bool refined = false;
    std::optional<double> targetMaxError;
    double achievedMaxError = 0.0;
    double rmse = 0.0;
    /// "error", "points" or "triangles": what stopped the refinement.
    std::string refineStop;
    std::uint64_t openHoleCells = 0;
    std::uint64_t holeTriangles = 0;
    std::uint64_t uncoveredCells = 0;
    /// Triangles removed by BuildOptions::maxEdge.
    std::uint64_t longEdgeTriangles = 0;
    BuildTimings timings;
};

/// Runs the build. Before reading anything it refuses an existing output without
/// `overwrite` (InvalidInputError) and a missing output directory (IoError); every error is a
/// terratin::Error whose message names the stage; the output is written atomically (see
/// io::writeTin). `progress` receives the fraction of the whole build (reading 10 %,
/// triangulating 40 %, writing 50 %).
BuildReport runBuild(const BuildOptions& options, const ProgressCallback& progress = {});

/// The report as one JSON object: input, output, format, crs {name, code}, counts {...},
/// triangulation {method, threads, history_bytes_per_point}, timings {read, triangulate,
/// validate, write, total} in seconds, validated; after a refinement also refine {max_error,
/// achieved_max_error, rmse, points, triangles, stop, open_hole_cells, hole_triangles,
/// uncovered_cells}; with maxEdge, long_edge_triangles.
std::string toJson(const BuildReport& report);

/// One human-readable line: points, duplicates, triangles and seconds per phase (after a
/// refinement: points, triangles, achieved max error and RMSE).
std::string toSummaryLine(const BuildReport& report);

} // namespace terratin

#pragma once
/// @file
/// `terratin build` as a library call: read -> triangulate -> write, timed and reported.
/// The CLI only maps its arguments onto BuildOptions and prints the BuildReport.

#include "terratin/io/las_reader.hpp"
#include "terratin/io/tin_writer.hpp"
#include "terratin/pipeline/option_spelling.hpp"
#include "terratin/progress.hpp"
#include "terratin/refine/refine.hpp"
#include "terratin/tile/refine_tiles.hpp"
#include "terratin/triangulate/triangulate.hpp"

#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace terratin {

/// Where breakline vertices get their elevation (--breakline-z).
enum class BreaklineZ {
    /// The line's z where it has one, else the surface's.
    Auto,
    /// The line's z; a line without z is an error.
    Line,
    /// The surface's: a DEM at its own cell centres bilinear in the four cells around the vertex,
    /// else (and where one of them has no data) the TIN of the inputs, linear in the triangle
    /// holding the vertex.
    Surface,
};

/// Everything `terratin build` can be asked.
struct BuildOptions {
    /// Inputs to merge, at least one: rasters (anything GDAL opens), LAS, delimited text, OGR
    /// point layers; see io::detectInputKind.
    std::vector<std::string> inputs;
    std::filesystem::path output;
    /// Instead of `output`, with a tiled simplification: the directory that gets each tile's
    /// TIN as its own file, tile_ROW_COLUMN.EXT in `format` (default GeoPackage), and
    /// tiles.gpkg, the index of the tiles' footprints; the TIN is never joined.
    std::filesystem::path tilesDir;
    /// A DEM's TIN built in tiles of this many cells a side (--tile-size, TileOptions::tileSize,
    /// tile/refine_tiles.hpp), simplified with refine->maxError, else at full resolution; 0:
    /// the whole DEM at once, unless memoryLimit sizes the tiles.
    std::size_t tileSize = 0;
    /// Bytes of memory a tiled build stays under (--memory-limit): the tile size follows from
    /// it unless tileSize is given (refused when that size would not fit), and `output` is
    /// written tile by tile, the TIN never held whole. With tileDistribution, each process's
    /// limit.
    std::optional<std::uint64_t> memoryLimit;
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

    // Point clouds (see io::LasReadOptions, io::TextReadOptions, io::OgrPointReadOptions).
    /// LAS: classification codes to keep (empty: all).
    std::vector<int> lasClasses;
    /// LAS: which returns to keep.
    io::LasReturns lasReturns = io::LasReturns::All;
    /// Text: the x, y, z columns, each a 1-based number or a header name (empty: automatic).
    std::vector<std::string> textColumns;
    /// Vector inputs: the numeric attribute holding z (empty: the geometry's z).
    std::string zField;
    /// Vector inputs: the layer to read (empty: the first point layer).
    std::string inputLayer;

    // Constraints.
    /// Breaklines: OGR line layers, "FILE" or "FILE|layername=NAME", reprojected like the
    /// inputs and clipped to their hull; every segment becomes a chain of TIN edges.
    std::vector<std::string> breaklines;
    /// The layer of every breakline source that names none (empty: the source's only layer).
    std::string breaklinesLayer;
    BreaklineZ breaklineZ = BreaklineZ::Auto;
    /// Clip area: an OGR polygon layer ("FILE" or "FILE|layername=NAME"); triangles outside it
    /// are removed and its boundary is constrained (z from the surface). Empty: none.
    std::string clip;
    /// Erase area: polygons cut out as holes, their boundaries constrained. Empty: none.
    std::string erase;
    /// Replace areas (hydro-flattening): polygons whose inside is flat at one elevation; no
    /// input point inside one is kept, and its boundary is a constrained ring at that
    /// elevation. Empty: none.
    std::string replace;
    /// The numeric attribute holding each replace polygon's elevation; empty: the lowest
    /// elevation of the inputs' surface on the polygon's boundary.
    std::string replaceZField;

    // Coordinate systems.
    /// Overrides every input's CRS (anything crs::crsFromUserInput accepts); required when an
    /// input has no CRS and the run needs one (--t_srs, or other inputs with a CRS).
    std::string sourceSrs;
    /// Reproject every point (x, y; z untouched) to this CRS before triangulating; the output
    /// carries it. Empty: the first input's CRS, or a UTM/UPS zone when that is geographic.
    std::string targetSrs;
    /// Keep geographic inputs in degrees instead of projecting them to their UTM/UPS zone.
    bool keepGeographic = false;
    /// Every elevation is multiplied by this (0.3048 turns feet into metres); finite, not 0.
    /// Units are never converted otherwise.
    double zFactor = 1.0;
    /// Receives notices as they happen (the UTM zone chosen, units left unconverted); they are
    /// also kept in BuildReport::notices. The CLI prints them on stderr.
    std::function<void(std::string_view)> notice;
    /// How runBuild's errors and notices name options (`--z-factor` or `z_factor`, see
    /// optionName): the modules it calls name them by keyword (markOption), and runBuild names
    /// them this way on the way out; parseBuildOptions sets it to the spelling of its caller.
    OptionSpelling optionSpelling = OptionSpelling::Keyword;
    /// Processes that share the tiles of a tiled build (TileOptions::distribution: terratin's
    /// MPI ranks); needs tileSize or memoryLimit. Only the coordinating process
    /// writes; the others return a report with servedTiles set and write nothing.
    TileDistribution* tileDistribution = nullptr;

    /// Terrain simplification (--max-error, --max-points, --max-triangles, --max-hole,
    /// --fill-holes): when set, the raster is read as a HeightGrid and refined instead of
    /// triangulating every valid cell; `refine->threads` 0 follows triangulation.threads and
    /// `validate` above applies to the refined TIN before its holes are cut.
    std::optional<RefineOptions> refine;
    /// Drop the triangles with an edge longer than this (planimetric, CRS units) from the final
    /// TIN, whatever built it (meant for point clouds, whose hull bridges gaps).
    std::optional<double> maxEdge;
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
    /// Reprojection of the inputs; included in `read`.
    double reproject = 0.0;
    /// The constraint layers read and inserted (with --max-error or --max-points, the cells
    /// checked and inserted after them too); included in `triangulate`.
    double constrain = 0.0;
};

/// What was read from one input.
struct InputReport {
    std::string path;
    /// "raster", "las", "laz", "text", "vector".
    std::string kind;
    /// The input's CRS (after --s_srs), empty when it has none.
    std::string crsName;
    std::string crsCode;
    /// Records in the file: raster cells, LAS point records, text data lines, OGR features.
    std::uint64_t records = 0;
    /// Records dropped by the class / return filters, withheld LAS points, OGR features
    /// without a point (or with a null z field).
    std::uint64_t filteredOut = 0;
    /// Rasters: nodata, masked or NaN cells.
    std::uint64_t skippedCells = 0;
    /// Points this input contributed.
    std::uint64_t points = 0;
    /// Of those, points merged into another point with the same x, y (from this input or an
    /// earlier one, whichever the duplicate policy keeps).
    std::uint64_t duplicates = 0;
    /// Its points were transformed to the target CRS.
    bool reprojected = false;
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
    /// Bytes of point-location history per input point (0 when the method keeps none, and
    /// after a simplification).
    double historyBytesPerPoint = 0.0;
    /// After a simplification: bytes of the refiner's mesh per vertex, its working memory
    /// beside the grid. 0 otherwise.
    double meshBytesPerPoint = 0.0;
    bool validated = false;
    /// Set when BuildOptions::refine was: what the refinement achieved, measured over every
    /// valid cell after the build (z units).
    bool refined = false;
    /// This process refined tiles for another (BuildOptions::tileDistribution) and wrote
    /// nothing; the other fields are unset.
    bool servedTiles = false;
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
    /// Breaklines: the lines inserted (after clipping to the hull: a line may become
    /// several), the lines clipped, and the vertices added for them (their own points, and
    /// where two of them cross).
    std::uint64_t breaklines = 0;
    std::uint64_t clippedBreaklines = 0;
    std::uint64_t constraintVertices = 0;
    std::uint64_t constraintCrossings = 0;
    /// Triangles removed outside the clip area or inside the erase areas.
    std::uint64_t areaTriangles = 0;
    /// Simplified constrained TINs: checks of the whole TIN after the constraints went in, and
    /// the cells inserted to bring every measured cell within the bound.
    std::uint64_t constraintPasses = 0;
    std::uint64_t constraintCells = 0;
    /// Replace polygons flattened, and the input points inside them left out.
    std::uint64_t replacePolygons = 0;
    std::uint64_t replacedPoints = 0;
    BuildTimings timings;

    /// Per input, in command-line order.
    std::vector<InputReport> inputs;
    /// Records dropped by the point-cloud filters, over all inputs.
    std::uint64_t filteredOut = 0;
    /// The inputs' CRS when they all share one (after --s_srs), "several" when they differ,
    /// empty when none has any.
    std::string sourceCrsName;
    std::string sourceCrsCode;
    /// "UTM zone 19N" / "UPS North" when geographic input was projected to its zone.
    std::string zone;
    /// Some input was reprojected.
    bool reprojected = false;
    double zFactor = 1.0;
    /// Notices given during the run (see BuildOptions::notice).
    std::vector<std::string> notices;
    /// Features (vector formats, all layers) or records (mesh formats: vertices + faces)
    /// written, and their rate over the write phase.
    std::uint64_t writeFeatures = 0;
    double writeFeaturesPerSecond = 0.0;
    /// GeoPackage: seconds of the write phase spent inserting rows and building spatial
    /// indexes (0 for the other formats).
    double writeRowSeconds = 0.0;
    double writeIndexSeconds = 0.0;
};

/// The writer's options for a build writing `format`: the output options of BuildOptions
/// (overwrite, layer, attributes, nodes, edges, append, spatial index, style); the CRS and the
/// vertices' raster cells are filled in once known. io::checkTinWriteOptions tells whether
/// they contradict each other.
io::TinWriteOptions tinWriteOptions(const BuildOptions& options, io::TinFormat format);

/// Throws InvalidInputError, with a message that names the option by its meaning (not by a
/// command-line flag), when an option of `options` is outside its documented range:
/// checkTriangulationOptions, checkRefineOptions (when `refine` is set), a band below 1, a
/// zFactor that is 0 or not finite, a maxEdge that is not a positive finite length, and
/// io::checkTinWriteOptions for the output format (given, or inferred from the output's
/// extension when that is known); keep_geographic with t_srs. Its messages name options by
/// keyword (runBuild names them as `optionSpelling` says). Reads nothing. runBuild calls it
/// first.
void checkBuildOptions(const BuildOptions& options);

/// Runs the build. Before reading anything it checks the options (checkBuildOptions) and
/// refuses an existing output without
/// `overwrite` (InvalidInputError) and a missing output directory (IoError); every error is a
/// terratin::Error whose message names the stage; the output is written atomically (see
/// io::writeTin). `progress` receives the fraction of the whole build (reading 10 %,
/// triangulating 40 %, writing 50 %).
/// Inputs are read in order, each in its own CRS (or `sourceSrs`), brought into the target
/// CRS (see BuildOptions::targetSrs) with x, y reprojected and z untouched, scaled by
/// `zFactor`, and merged in input order; duplicates across inputs are merged by the
/// triangulation's duplicate policy. Without any reprojection and with zFactor 1, vertex
/// coordinates and elevations are exactly the readers' values. Throws CrsError when an input
/// lacks a CRS the run needs, or a CRS is unusable; InvalidInputError for a zFactor that is 0
/// or not finite.
BuildReport runBuild(const BuildOptions& options, const ProgressCallback& progress = {});

/// The report as one JSON object: input, output, format, crs {name, code}, counts {...},
/// triangulation {method, threads, history_bytes_per_point}, timings {read, triangulate,
/// validate, write, total, reproject} in seconds, validated; then source_crs {name, code},
/// target_crs {name, code}, zone, reprojected, z_factor, inputs [{path, kind, crs {name, code},
/// records, filtered_out, skipped_cells, points, duplicates, reprojected}], notices [...];
/// after a refinement also refine {max_error, achieved_max_error, rmse, points, triangles,
/// stop, open_hole_cells, hole_triangles, uncovered_cells}; with maxEdge, long_edge_triangles;
/// writing {features, features_per_second}.
std::string toJson(const BuildReport& report);

/// One human-readable line: points, duplicates, triangles and seconds per phase (after a
/// refinement: points, triangles, achieved max error and RMSE).
std::string toSummaryLine(const BuildReport& report);

/// One line per input ("input 1: a.las (las, EPSG:2992): 110000 records, 83893 filtered out,
/// 26107 points, 0 duplicates") and one for the CRS ("CRS: EPSG:4326 -> EPSG:32619 (UTM zone
/// 19N)"), each ending in a newline.
std::string toInputSummary(const BuildReport& report);

} // namespace terratin

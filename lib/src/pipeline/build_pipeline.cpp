#include "terratin/pipeline/build_pipeline.hpp"

#include "../stopwatch.hpp"
#include "breaklines.hpp"
#include "constrained_refine.hpp"
#include "gather_inputs.hpp"
#include "memory_budget.hpp"
#include "refine_placement.hpp"
#include "streamed_tin.hpp"
#include "terratin/constrain/constrained_validation.hpp"
#include "terratin/crs/grid_projection.hpp"
#include "terratin/error.hpp"
#include "terratin/gdal_error.hpp"
#include "terratin/io/height_grid_reader.hpp"
#include "terratin/io/input_reader.hpp"
#include "terratin/io/raster_reader.hpp"
#include "terratin/pipeline/build_option_table.hpp"
#include "terratin/refine/mesh_filter.hpp"
#include "terratin/refine/tile_distribution.hpp"
#include "terratin/triangulate/mesh_validation.hpp"
#include "terratin/triangulate/triangulate.hpp"
#include "tile_files.hpp"

#include <ogr_spatialref.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <future>
#include <optional>
#include <sstream>
#include <string>
#include <system_error>
#include <utility>

namespace terratin {

namespace {

// Share of the whole run each phase gets on the progress bar, roughly their usual cost.
constexpr double kReadShare = 0.1;
constexpr double kTriangulateShare = 0.4;
constexpr double kWriteShare = 0.5;

using detail::Stopwatch;

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

/// Throws when `validation` found a problem (MeshValidation or ConstrainedValidation).
template <class Validation> void checkValid(const Validation& validation, const char* what) {
    if (!validation.ok())
        throw Error(std::string("Validation: the mesh is not an exact ") + what +
                    " triangulation: " +
                    (validation.problems.empty() ? std::string("unknown problem")
                                                 : validation.problems.front()));
}

std::string formatName(io::TinFormat format) {
    return std::string(io::tinFormatName(format));
}

bool isConstraintVertex(std::uint32_t source) {
    return source == kConstraintPointSource || source == kIntersectionSource;
}

// Each breakline's vertices, as points (LandXML writes them so; a vertex number would not
// survive dropping triangles).
std::vector<std::vector<Point3>> chainPoints(const ConstrainedTin& constrained,
                                             const TinMesh& mesh) {
    std::vector<std::vector<Point3>> lines;
    lines.reserve(constrained.chains.size());
    for (const std::vector<std::uint32_t>& chain : constrained.chains) {
        if (chain.size() < 2)
            continue;
        std::vector<Point3>& line = lines.emplace_back();
        for (const std::uint32_t vertex : chain)
            line.push_back(mesh.vertices[vertex]);
    }
    return lines;
}

bool hasConstraints(const BuildOptions& options) {
    return !options.breaklines.empty() || !options.clip.empty() || !options.erase.empty() ||
           !options.replace.empty();
}

// The per-half-edge flags of the triangles `drop` keeps, in order (dropTriangles keeps the
// kept triangles' order and corners).
void keepEdgesOfKeptTriangles(MeshArray<std::uint8_t>& edgeFlags,
                              const std::vector<std::uint8_t>& drop) {
    if (edgeFlags.empty())
        return;
    std::size_t kept = 0;
    for (std::size_t t = 0; t < drop.size(); ++t)
        if (drop[t] == 0) {
            std::copy_n(edgeFlags.begin() + static_cast<std::ptrdiff_t>(3 * t), 3,
                        edgeFlags.begin() + static_cast<std::ptrdiff_t>(3 * kept));
            ++kept;
        }
    edgeFlags.resize(3 * kept);
}

// The raster cell of every vertex, for the GeoPackage nodes layer: `cellOf(source)` is the
// row-major cell index of input point `source`.
template <class CellOf>
std::vector<io::RasterCell> vertexCells(const TinMesh& mesh, std::uint64_t width, CellOf cellOf) {
    std::vector<io::RasterCell> cells(mesh.vertexCount());
    for (std::size_t v = 0; v < cells.size(); ++v) {
        if (isConstraintVertex(mesh.sourceIndex[v])) {
            cells[v] = {-1, -1}; // a breakline's point or crossing: no cell
            continue;
        }
        const std::uint64_t cell = cellOf(mesh.sourceIndex[v]);
        cells[v] = {static_cast<std::int64_t>(cell / width),
                    static_cast<std::int64_t>(cell % width)};
    }
    return cells;
}

// The nodes' cells when the TIN comes from one raster (row and column have no meaning for
// point clouds, nor across several rasters); empty otherwise.
std::vector<io::RasterCell> vertexCells(const TinMesh& mesh,
                                        const detail::GatheredInputs& gathered) {
    if (gathered.rasterWidth == 0)
        return {};
    return vertexCells(mesh, gathered.rasterWidth,
                       [&](std::uint32_t source) { return gathered.cellIndex[source]; });
}

// The write phase's figures and the total; the last progress call.
BuildReport finishReport(BuildReport report, const io::TinWriteResult& written,
                         const Stopwatch& writeTime, const Stopwatch& totalTime,
                         const ProgressCallback& progress) {
    report.timings.write = writeTime.seconds();
    report.writeFeatures = written.features;
    report.writeRowSeconds = written.rowSeconds;
    report.writeIndexSeconds = written.indexSeconds;
    report.writeFeaturesPerSecond =
        report.timings.write > 0.0 ? static_cast<double>(written.features) / report.timings.write
                                   : 0.0;
    report.timings.total = totalTime.seconds();
    if (progress)
        progress(1.0, "done");
    return report;
}

// The constrained TIN as the writers take it: its constrained edges and, for LandXML (the one
// format that writes them), its breaklines go into `writeOptions` (the breaklines before any
// triangle is dropped), and the triangles `drop` marks (none when empty) are removed. Returns
// how many were removed.
std::size_t takeConstrainedOutput(ConstrainedTin& tin, const std::vector<std::uint8_t>& drop,
                                  io::TinWriteOptions& writeOptions) {
    writeOptions.constrainedEdges = std::move(tin.constrained);
    if (writeOptions.format == io::TinFormat::LandXml)
        writeOptions.breaklines = chainPoints(tin, tin.mesh);
    if (drop.empty())
        return 0;
    keepEdgesOfKeptTriangles(writeOptions.constrainedEdges, drop);
    const std::size_t removed = dropTriangles(tin.mesh, drop);
    if (tin.mesh.triangleCount() == 0)
        throw InvalidInputError("Build: no triangle is left inside the clip area and outside "
                                "the erase areas");
    return removed;
}

// The simplified constrained TIN for the writers (validated when asked), and its figures in
// `report` in place of the refiner's.
TinMesh takeConstrainedMesh(detail::ConstrainedRefinement corrected, const BuildOptions& options,
                            io::TinWriteOptions& writeOptions, BuildReport& report) {
    if (options.validate) {
        checkValid(validateConstrainedDelaunay(corrected.build.tin), "constrained Delaunay");
        report.validated = true;
    }
    report.achievedMaxError = corrected.maxError;
    report.rmse = corrected.rmse;
    report.uncoveredCells = corrected.uncoveredCells;
    report.holeTriangles = corrected.holeTriangles;
    report.openHoleCells = corrected.openHoleCells;
    report.constraintPasses = corrected.passes;
    report.constraintCells = corrected.insertedCells;
    if (corrected.limitReached)
        report.refineStop = options.refine->maxPoints ? toString(RefineStop::PointLimit)
                                                      : toString(RefineStop::TriangleLimit);
    report.areaTriangles =
        takeConstrainedOutput(corrected.build.tin, corrected.drop, writeOptions) -
        corrected.holeTriangles;
    return std::move(corrected.build.tin.mesh);
}

// runBuild with BuildOptions::refine: the raster as a HeightGrid, refined, holes cut, written.
// The refiner works on one raster's grid; scaling z would change what E means.
// What takes a DEM alone, as its options name it: tiling, or a simplification.
std::string demOnlyWork(const BuildOptions& options) {
    const OptionSpelling spelling = options.optionSpelling;
    if (options.memoryLimit)
        return "Tiling (" + optionName("memory_limit", spelling) + ")";
    if (options.refine && options.refine->tileSize > 0)
        return "Tiling (" + optionName("tile_size", spelling) + ")";
    return "Simplification (" + optionName("max_error", spelling) + "...)";
}

// What the simplified and tiled builds refuse of the options alone, with the other option
// checks: contradicting options are a usage error, found before anything is read.
void checkDemOnlyOptions(const BuildOptions& options) {
    const OptionSpelling spelling = options.optionSpelling;
    if (options.zFactor != 1.0)
        throw InvalidInputError(demOnlyWork(options) + " does not combine with " +
                                optionName("z_factor", spelling) +
                                "; scale the DEM first (gdal_calc)");
    const bool tiled = options.memoryLimit || options.refine->tileSize > 0;
    if (tiled && hasConstraints(options))
        throw InvalidInputError(demOnlyWork(options) +
                                " does not combine with breaklines, clip, erase or replace "
                                "polygons yet");
}

void checkOneRasterInput(const BuildOptions& options) {
    checkDemOnlyOptions(options);
    if (options.inputs.size() != 1)
        throw InvalidInputError(demOnlyWork(options) + " takes exactly one raster input");
    if (io::detectInputKind(options.inputs.front()) != io::InputKind::Raster)
        throw InvalidInputError(demOnlyWork(options) + " takes a DEM raster; '" +
                                options.inputs.front() +
                                "' is a point cloud or vector layer: triangulate it without " +
                                "those options, or grid it first (gdal_grid)");
}

RefineOptions refineOptionsOf(const BuildOptions& options) {
    RefineOptions refineOptions = *options.refine;
    if (refineOptions.threads == 0)
        refineOptions.threads = options.triangulation.threads;
    refineOptions.validate = options.validate;
    refineOptions.distribution = options.tileDistribution;
    return refineOptions;
}

/// `points`: the TIN's, which result.mesh holds unless the tiles went to a sink.
void reportRefinement(const RefineResult& result, const RefineOptions& refineOptions,
                      std::size_t points, BuildReport& report) {
    report.refined = true;
    report.targetMaxError = refineOptions.maxError;
    report.achievedMaxError = result.maxError;
    report.rmse = result.rmse;
    report.refineStop = toString(result.stop);
    report.openHoleCells = result.openHoleCells;
    report.holeTriangles = result.droppedTriangles;
    report.uncoveredCells = result.uncoveredCells;
    report.validated = result.validated;
    report.method = "refine";
    report.threads = result.threads;
    report.meshBytesPerPoint = static_cast<double>(result.meshBytes) /
                               static_cast<double>(std::max<std::size_t>(points, 1));
}

/// The simplified TIN, its long edges dropped, written in `targetWkt`; the report finished.
BuildReport writeRefinedTin(TinMesh mesh, int gridWidth, const std::string& targetWkt,
                            const BuildOptions& options, io::TinWriteOptions writeOptions,
                            const ProgressCallback& progress, BuildReport report,
                            const Stopwatch& refineTime, const Stopwatch& totalTime) {
    report.points = mesh.vertexCount();
    report.vertices = mesh.vertexCount();
    if (options.maxEdge) {
        const std::vector<std::uint8_t> drop = longEdgeTriangles(mesh, *options.maxEdge);
        keepEdgesOfKeptTriangles(writeOptions.constrainedEdges, drop);
        report.longEdgeTriangles = dropTriangles(mesh, drop);
    }
    report.triangles = mesh.triangleCount();
    report.timings.triangulate = refineTime.seconds();

    const Stopwatch writeTime;
    writeOptions.crsWkt = targetWkt;
    if (options.nodes) // the refiner's sourceIndex is the cell index
        writeOptions.vertexCells =
            vertexCells(mesh, static_cast<std::uint64_t>(gridWidth),
                        [](std::uint32_t cell) { return std::uint64_t{cell}; });
    const io::TinWriteResult written =
        io::writeTin(mesh, options.output, writeOptions,
                     phaseProgress(progress, kReadShare + kTriangulateShare, kWriteShare));
    return finishReport(std::move(report), written, writeTime, totalTime, progress);
}

// The counts of a TIN whose tiles went to files as they came, never joined.
void reportTileCounts(std::uint64_t points, std::uint64_t triangles, const Stopwatch& refineTime,
                      BuildReport& report) {
    report.points = points;
    report.vertices = points;
    report.triangles = triangles;
    report.timings.triangulate = refineTime.seconds(); // the tiles' writing included
}

// --tiles-dir: the tiles are written as they came; the index last, which keeps them all.
BuildReport commitTileFiles(detail::TileFiles& files, BuildReport report,
                            const Stopwatch& refineTime, const Stopwatch& totalTime,
                            const ProgressCallback& progress) {
    reportTileCounts(files.points(), files.triangles(), refineTime, report);
    const Stopwatch writeTime;
    files.commit();
    io::TinWriteResult written;
    written.features = files.features();
    return finishReport(std::move(report), written, writeTime, totalTime, progress);
}

// --memory-limit: the tiles went to the output as they came; its end (the spatial index) now.
BuildReport finishStreamedTin(detail::StreamedTin& tin, const std::uint64_t writerBytes,
                              const BuildOptions& options, BuildReport report,
                              const Stopwatch& refineTime, const Stopwatch& totalTime,
                              const ProgressCallback& progress) {
    reportTileCounts(tin.points(), tin.triangles(), refineTime, report);
    if (tin.heldBytes() > writerBytes)
        detail::notify(options, report,
                       "the spatial index kept " + std::to_string(tin.heldBytes() >> 20U) +
                           " MiB, more than the share of " +
                           optionName("memory_limit", options.optionSpelling) +
                           " set aside for it; give a larger limit or " +
                           optionName("no_spatial_index", options.optionSpelling));
    const Stopwatch writeTime;
    const io::TinWriteResult written =
        tin.finish(phaseProgress(progress, kReadShare + kTriangulateShare, kWriteShare));
    return finishReport(std::move(report), written, writeTime, totalTime, progress);
}

// Tiles (--tile-size): the raster read a tile's window at a time, never whole. What tiles do not
// take yet is refused with the options' names before anything is read.
BuildReport runTiledBuild(const BuildOptions& options, io::TinWriteOptions writeOptions,
                          const ProgressCallback& progress, BuildReport report,
                          const Stopwatch& totalTime) {
    checkOneRasterInput(options);
    io::RasterReadOptions readOptions;
    readOptions.band = options.band;
    io::RasterCells cells(options.inputs.front(), readOptions);
    HeightGrid extent; // the raster's shape, without its cells
    extent.width = cells.width();
    extent.height = cells.height();
    extent.geoTransform = cells.geoTransform();
    const detail::RefineCrs crs =
        detail::chooseRefineCrs(options, extent.extentCentre(), cells.crsWkt(), report);
    describeCrs(crs.target, report);
    report.rasterCells = extent.cellCount();

    // Reading is part of the refinement: each tile reads its own cells.
    const Stopwatch refineTime;
    RefineOptions refineOptions = refineOptionsOf(options);
    if (crs.movesCells()) {
        // A geographic DEM is refined in its UTM zone, each tile at its cells' positions.
        refineOptions.cellPositions = [source = crs.source,
                                       target = crs.target](const HeightGrid& window) {
            return crs::projectCellCentres(window, source, target);
        };
        report.reprojected = true;
    }
    const bool coordinates =
        options.tileDistribution == nullptr || options.tileDistribution->coordinates();
    std::optional<detail::MemoryBudget> budget;
    std::optional<detail::GdalCacheCap> gdalCache;
    if (options.memoryLimit) {
        const std::size_t margin = refineOptions.fillHoles ? 0 : refineOptions.maxHole;
        const OptionNamer namer = optionNamer(options.optionSpelling);
        // planTiles sized the tiles before the CRS was known; cells that move take more a
        // cell, so such tiles are sized again.
        if (crs.movesCells() &&
            refineOptions.tileSize ==
                detail::memoryBudget(*options.memoryLimit, margin, 0, namer).tileSize)
            refineOptions.tileSize = 0;
        budget = detail::memoryBudget(*options.memoryLimit, margin, refineOptions.tileSize, namer,
                                      crs.movesCells());
        refineOptions.tileSize = budget->tileSize;
        gdalCache.emplace(budget->gdalCacheBytes);
        refineOptions.earlyTileBytes = budget->tileBytes;
        if (coordinates)
            detail::notify(options, report,
                           "tiles of " + std::to_string(budget->tileSize) +
                               " cells a side within " +
                               optionName("memory_limit", options.optionSpelling));
    }
    writeOptions.crsWkt = crs.target;
    const auto keptTriangles = [&](TinMesh& tin) {
        if (options.maxEdge)
            report.longEdgeTriangles += dropLongEdgeTriangles(tin, *options.maxEdge);
        return tin.triangleCount() > 0;
    };
    // A tile's sourceIndex is the grid's cell index.
    const auto cellsOfTile = [&](const TinMesh& tin) {
        return options.nodes ? vertexCells(tin, static_cast<std::uint64_t>(extent.width),
                                           [](std::uint32_t cell) { return std::uint64_t{cell}; })
                             : std::vector<io::RasterCell>{};
    };
    std::optional<detail::TileFiles> files;
    std::optional<detail::StreamedTin> streamed;
    if (!options.tilesDir.empty() && coordinates) {
        files.emplace(options.tilesDir, extent, refineOptions.tileSize, writeOptions,
                      refineOptions.cellPositions);
        refineOptions.tileSink = [&](std::size_t tile, TinMesh tin) {
            if (!keptTriangles(tin))
                return; // every triangle too long: no file
            files->write(tile, tin, cellsOfTile(tin));
        };
    } else if (options.memoryLimit && coordinates) {
        streamed.emplace(options.output, writeOptions, extent.width, extent.height,
                         refineOptions.tileSize,
                         optionName("memory_limit", options.optionSpelling));
        refineOptions.tileSink = [&](std::size_t tile, TinMesh tin) {
            keptTriangles(tin); // a tile's vertices stay, as in the joined TIN
            streamed->write(tile, tin, cellsOfTile(tin));
        };
    }
    RefineResult result = refineTiles(cells, refineOptions,
                                      phaseProgress(progress, 0.0, kReadShare + kTriangulateShare));
    if (!coordinates) {
        report.servedTiles = true;
        return report;
    }
    report.skippedCells = report.rasterCells - result.validCells;
    reportRefinement(result, refineOptions,
                     files      ? files->points()
                     : streamed ? streamed->points()
                                : result.mesh.vertexCount(),
                     report);
    if (files)
        return commitTileFiles(*files, std::move(report), refineTime, totalTime, progress);
    if (streamed)
        return finishStreamedTin(*streamed, budget->writerBytes, options, std::move(report),
                                 refineTime, totalTime, progress);
    return writeRefinedTin(std::move(result.mesh), extent.width, crs.target, options,
                           std::move(writeOptions), progress, std::move(report), refineTime,
                           totalTime);
}

BuildReport runRefineBuild(const BuildOptions& options, io::TinWriteOptions writeOptions,
                           const ProgressCallback& progress, BuildReport report,
                           const Stopwatch& totalTime) {
    if (options.refine->tileSize > 0)
        return runTiledBuild(options, std::move(writeOptions), progress, std::move(report),
                             totalTime);
    checkOneRasterInput(options);
    // The constraint layers are read while the DEM is.
    std::future<detail::ConstraintLayers> constraintLayers;
    if (hasConstraints(options))
        constraintLayers = detail::startReadingConstraintLayers(options);
    const Stopwatch readTime;
    io::RasterReadOptions readOptions;
    readOptions.band = options.band;
    io::HeightGridRaster raster = io::readHeightGrid(options.inputs.front(), readOptions,
                                                     phaseProgress(progress, 0.0, kReadShare));
    report.rasterCells = raster.grid.cellCount();
    report.skippedCells = raster.skippedCells;
    report.timings.read = readTime.seconds();
    // A geographic raster is refined in its UTM zone, at its cells' projected positions.
    const detail::RefinePlacement placement =
        detail::placeRefinedCells(options, raster.grid, raster.crsWkt, report);
    describeCrs(placement.targetWkt, report);

    const bool constrained = hasConstraints(options);
    const Stopwatch refineTime;
    RefineOptions refineOptions = refineOptionsOf(options);
    refineOptions.keepHoleTriangles = constrained;
    refineOptions.measure = !constrained; // refineWithConstraints measures every cell
    // With constraints, the refiner has most of the phase and the cells' insertion the rest.
    const double refineShare = constrained ? 0.8 * kTriangulateShare : kTriangulateShare;
    const ProgressCallback refineProgress = phaseProgress(progress, kReadShare, refineShare);
    detail::ConstraintSources sources;
    std::size_t replacedCells = 0;
    if (constrained) {
        const Stopwatch constrainTime;
        // A projected (geographic) DEM's cells are no longer on its grid: no bilinear z then.
        sources = detail::readConstraintSources(
            constraintLayers.get(), options, placement.targetWkt,
            placement.positions.empty() ? &raster.grid : nullptr, report);
        replacedCells = detail::leaveOutAreaCells(raster.grid, placement.positions, sources);
        refineOptions.spareVertices = sources.spareVertices();
        report.timings.constrain = constrainTime.seconds();
    }
    RefineResult result =
        placement.positions.empty()
            ? refine(raster.grid, refineOptions, refineProgress)
            : refine(raster.grid, placement.positions, refineOptions, refineProgress);
    reportRefinement(result, refineOptions, result.mesh.vertexCount(), report);
    TinMesh mesh = std::move(result.mesh);
    if (constrained) {
        const Stopwatch constrainTime;
        detail::ConstrainedRefinement corrected = detail::refineWithConstraints(
            raster.grid, placement.positions, std::move(mesh), options, std::move(sources), report,
            phaseProgress(progress, kReadShare + refineShare, kTriangulateShare - refineShare));
        mesh = takeConstrainedMesh(std::move(corrected), options, writeOptions, report);
        report.replacedPoints += replacedCells;
        report.timings.constrain += constrainTime.seconds();
    }
    const int gridWidth = raster.grid.width;
    raster.grid = {}; // the mesh holds its own vertices
    return writeRefinedTin(std::move(mesh), gridWidth, placement.targetWkt, options,
                           std::move(writeOptions), progress, std::move(report), refineTime,
                           totalTime);
}

} // namespace

io::TinWriteOptions tinWriteOptions(const BuildOptions& options, io::TinFormat format) {
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
    writeOptions.optionName = optionNamer(options.optionSpelling);
    return writeOptions;
}

namespace {

// Tiles without a maximum error or a limit are full resolution: every valid cell a vertex.
RefineOptions withEveryCellTiles(RefineOptions refine) {
    if (refine.tileSize > 0 && !refine.maxError && !refine.maxPoints && !refine.maxTriangles)
        refine.everyCell = true;
    return refine;
}

} // namespace

void checkBuildOptions(const BuildOptions& options) {
    checkTriangulationOptions(options.triangulation);
    if (options.refine)
        checkRefineOptions(withEveryCellTiles(*options.refine));
    if (options.band < 1)
        throw InvalidInputError("Build: the raster band must be 1 or more (got " +
                                std::to_string(options.band) + ")");
    if (!std::isfinite(options.zFactor) || options.zFactor == 0.0)
        throw InvalidInputError("Build: the z factor must be a finite number other than 0");
    if (!options.replaceZField.empty() && options.replace.empty())
        throw InvalidInputError("Build: " + optionName("replace_z_field", options.optionSpelling) +
                                " names the field of " +
                                optionName("replace", options.optionSpelling) +
                                " polygons: give them too");
    if (options.maxEdge && (!std::isfinite(*options.maxEdge) || *options.maxEdge <= 0.0))
        throw InvalidInputError("Build: the longest edge kept must be a positive length");
    if (options.refine)
        checkDemOnlyOptions(options);
    const bool tilesDir = !options.tilesDir.empty();
    if (tilesDir && !options.memoryLimit && (!options.refine || options.refine->tileSize == 0))
        throw InvalidInputError("Build: " + optionName("tiles_dir", options.optionSpelling) +
                                " writes tiles: give " +
                                optionName("tile_size", options.optionSpelling) + " or " +
                                optionName("memory_limit", options.optionSpelling));
    if (!options.format)
        return;
    const io::TinWriteOptions writeOptions = tinWriteOptions(options, *options.format);
    io::checkTinWriteOptions(writeOptions);
    if (options.memoryLimit && !tilesDir)
        io::detail::checkTinStreamOptions(writeOptions,
                                          optionName("memory_limit", options.optionSpelling));
}

namespace {

// --memory-limit without --tile-size sizes the tiles, and tiles without a maximum error or a
// limit are full resolution. Empty when there is nothing to plan.
std::optional<BuildOptions> planTiles(const BuildOptions& options) {
    RefineOptions refine = options.refine.value_or(RefineOptions{});
    const bool sized = options.memoryLimit && refine.tileSize == 0;
    if (sized)
        refine.tileSize =
            detail::memoryBudget(*options.memoryLimit, refine.fillHoles ? 0 : refine.maxHole, 0,
                                 optionNamer(options.optionSpelling))
                .tileSize;
    refine = withEveryCellTiles(refine);
    if (!sized && (!options.refine || refine.everyCell == options.refine->everyCell))
        return std::nullopt;
    BuildOptions planned = options;
    planned.refine = refine;
    return planned;
}

BuildReport runBuildStages(const BuildOptions& options, const ProgressCallback& progress) {
    if (const std::optional<BuildOptions> planned = planTiles(options))
        return runBuildStages(*planned, progress);
    const Stopwatch totalTime;
    const bool tilesDir = !options.tilesDir.empty();
    const io::TinFormat format =
        options.format ? *options.format
        : tilesDir     ? io::TinFormat::GeoPackage
                       : io::tinFormatFromPath(options.output, optionNamer(options.optionSpelling));
    io::TinWriteOptions writeOptions = tinWriteOptions(options, format);
    io::checkTinWriteOptions(writeOptions); // contradictory options fail before reading
    if (tilesDir && (!options.refine || options.refine->tileSize == 0))
        throw InvalidInputError("Build: " + optionName("tiles_dir", options.optionSpelling) +
                                " writes tiles: give " +
                                optionName("tile_size", options.optionSpelling) + " or " +
                                optionName("memory_limit", options.optionSpelling));
    if (!tilesDir)
        io::checkTinOutput(options.output, writeOptions); // an output that would be refused too
    if (options.memoryLimit && !tilesDir)
        io::detail::checkTinStreamOptions(writeOptions,
                                          optionName("memory_limit", options.optionSpelling));

    BuildReport report;
    {
        const std::vector<std::string>& paths = options.inputs;
        for (std::size_t i = 0; i < paths.size(); ++i)
            report.input += (i > 0 ? ", " : "") + paths[i];
    }
    report.output = (tilesDir ? options.tilesDir : options.output).string();
    report.format = formatName(format);
    if (options.tileDistribution != nullptr && (!options.refine || options.refine->tileSize == 0))
        throw InvalidInputError("Build: several processes share the work only by tiles: give " +
                                optionName("tile_size", options.optionSpelling) + " or " +
                                optionName("memory_limit", options.optionSpelling));
    if (options.refine)
        return runRefineBuild(options, writeOptions, progress, std::move(report), totalTime);

    // The constraint layers are read while the inputs are.
    std::future<detail::ConstraintLayers> constraintLayers;
    if (hasConstraints(options))
        constraintLayers = detail::startReadingConstraintLayers(options);
    const Stopwatch readTime;
    detail::GatheredInputs gathered =
        detail::gatherInputs(options, report, phaseProgress(progress, 0.0, kReadShare));
    describeCrs(gathered.crsWkt, report);
    report.timings.read = readTime.seconds();

    const Stopwatch triangulateTime;
    std::optional<detail::ConstraintSources> sources;
    TriangulationOptions triangulationOptions = options.triangulation;
    if (hasConstraints(options)) {
        const Stopwatch constrainTime;
        const std::optional<HeightGrid> dem =
            detail::cellSurface(gathered, options.triangulation.threads);
        sources = detail::readConstraintSources(constraintLayers.get(), options, gathered.crsWkt,
                                                dem ? &*dem : nullptr, report);
        triangulationOptions.spareVertices = sources->spareVertices();
        report.timings.constrain = constrainTime.seconds();
    }
    TriangulationResult triangulation =
        triangulate(gathered.points, triangulationOptions,
                    phaseProgress(progress, kReadShare, kTriangulateShare));
    gathered.points = {}; // the mesh holds its own copy of the vertices
    detail::countDuplicatesPerInput(gathered.offsets, triangulation.mesh.sourceIndex, report);
    report.duplicates = triangulation.duplicatePoints;
    report.vertices = triangulation.mesh.vertexCount();
    report.triangles = triangulation.mesh.triangleCount();
    report.method = toString(triangulation.method);
    report.threads = triangulation.threads;
    report.historyBytesPerPoint = static_cast<double>(triangulation.historyBytes) /
                                  static_cast<double>(std::max<std::uint64_t>(report.points, 1));
    std::optional<detail::ConstrainedBuild> constrained;
    if (sources) {
        const Stopwatch constrainTime;
        constrained = detail::addConstraints(std::move(triangulation.mesh), options, report,
                                             std::move(*sources));
        report.timings.constrain += constrainTime.seconds();
        report.vertices = constrained->tin.mesh.vertexCount();
        report.triangles = constrained->tin.mesh.triangleCount();
    }
    report.timings.triangulate = triangulateTime.seconds();

    if (options.validate) {
        const Stopwatch validateTime;
        if (constrained)
            checkValid(validateConstrainedDelaunay(constrained->tin), "constrained Delaunay");
        else
            checkValid(validateDelaunay(triangulation.mesh), "Delaunay");
        report.validated = true;
        report.timings.validate = validateTime.seconds();
    }

    if (constrained) {
        report.areaTriangles =
            takeConstrainedOutput(constrained->tin, constrained->outsideArea, writeOptions);
        triangulation.mesh = std::move(constrained->tin.mesh);
        report.vertices = triangulation.mesh.vertexCount();
        report.triangles = triangulation.mesh.triangleCount();
    }
    if (options.maxEdge) {
        const std::vector<std::uint8_t> drop =
            longEdgeTriangles(triangulation.mesh, *options.maxEdge);
        keepEdgesOfKeptTriangles(writeOptions.constrainedEdges, drop);
        report.longEdgeTriangles = dropTriangles(triangulation.mesh, drop);
        report.triangles = triangulation.mesh.triangleCount();
    }

    const Stopwatch writeTime;
    writeOptions.crsWkt = gathered.crsWkt;
    if (options.nodes)
        writeOptions.vertexCells = vertexCells(triangulation.mesh, gathered);
    const io::TinWriteResult written =
        io::writeTin(triangulation.mesh, options.output, writeOptions,
                     phaseProgress(progress, kReadShare + kTriangulateShare, kWriteShare));
    return finishReport(std::move(report), written, writeTime, totalTime, progress);
}

} // namespace

BuildReport runBuild(const BuildOptions& options, const ProgressCallback& progress) {
    checkBuildOptions(options);
    try {
        return runBuildStages(options, progress);
    } catch (const std::system_error& error) {
        // std::thread reports a thread it cannot start as a system_error (EAGAIN), not as
        // bad_alloc, when the address space (ulimit -v) or the process limit runs out.
        if (error.code() == std::errc::resource_unavailable_try_again ||
            error.code() == std::errc::not_enough_memory)
            throw Error("Build: out of memory: cannot start another thread (" +
                        error.code().message() + ")");
        throw;
    }
}

} // namespace terratin

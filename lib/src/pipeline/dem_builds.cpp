#include "builds.hpp"
#include "constrained_refine.hpp"
#include "memory_budget.hpp"
#include "refine_placement.hpp"
#include "streamed_tin.hpp"
#include "terratin/constrain/constrained_validation.hpp"
#include "terratin/crs/grid_projection.hpp"
#include "terratin/io/height_grid_reader.hpp"
#include "terratin/io/input_reader.hpp"
#include "terratin/pipeline/build_option_table.hpp"
#include "terratin/tile/refine_tiles.hpp"
#include "terratin/tile/tile_distribution.hpp"
#include "terratin/triangulate/mesh_filter.hpp"
#include "tile_files.hpp"

#include <algorithm>
#include <future>
#include <memory>
#include <optional>
#include <utility>

namespace terratin::detail {

namespace {

// What takes a DEM alone, as its options name it: tiling, or a simplification.
std::string demOnlyWork(const BuildOptions& options) {
    if (options.memoryLimit)
        return "Tiling (" + markOption("memory_limit") + ")";
    if (options.tileSize > 0)
        return "Tiling (" + markOption("tile_size") + ")";
    return "Simplification (" + markOption("max_error") + "...)";
}

// The refiner works on one raster's grid.
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

// The simplified constrained TIN for the writers (validated when asked), and its figures in
// the report in place of the refiner's.
TinMesh takeConstrainedMesh(ConstrainedRefinement corrected, BuildRun& run) {
    const BuildOptions& options = run.options();
    BuildReport& report = run.report();
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
        takeConstrainedOutput(corrected.build.tin, corrected.drop, run.writeOptions()) -
        corrected.holeTriangles;
    return std::move(corrected.build.tin.mesh);
}

// A refined TIN's vertices: each vertex's sourceIndex is its cell's index in the grid.
VertexRasterCells gridCells(int gridWidth) {
    return {[](std::uint32_t cell) { return std::uint64_t{cell}; },
            static_cast<std::uint64_t>(gridWidth)};
}

// The refined TIN, whose sourceIndex is the grid's cell index, for the whole-file sink.
TinProduct refinedProduct(TinMesh mesh, int gridWidth, const std::string& crsWkt,
                          BuildReport& report) {
    report.points = mesh.vertexCount();
    report.vertices = mesh.vertexCount();
    return {std::move(mesh), crsWkt, gridCells(gridWidth)};
}

// The counts of a TIN whose tiles went to files as they came, never joined.
void reportTileCounts(std::uint64_t points, std::uint64_t triangles, const Stopwatch& refineTime,
                      BuildReport& report) {
    report.points = points;
    report.vertices = points;
    report.triangles = triangles;
    report.timings.triangulate = refineTime.seconds(); // the tiles' writing included
}

// --memory-limit: the tiles went to the output as they came; a notice when the spatial
// index, which the writer holds to the end, outgrew its share of the limit.
void noticeHeldIndex(const StreamedTin& tin, std::uint64_t writerBytes, BuildRun& run) {
    if (tin.heldBytes() > writerBytes)
        run.notify("the spatial index kept " + std::to_string(tin.heldBytes() >> 20U) +
                   " MiB, more than the share of " + markOption("memory_limit") +
                   " set aside for it; give a larger limit or " + markOption("no_spatial_index"));
}

// Where the tiles go as they come (a directory of tiles, or one file streamed); none when
// they are joined into one TIN (or this process only refines what it is handed).
std::unique_ptr<TinSink> tileSink(BuildRun& run, const HeightGrid& extent, const TileOptions& tiles,
                                  bool coordinates) {
    const BuildOptions& options = run.options();
    if (!coordinates)
        return nullptr;
    if (!options.tilesDir.empty())
        return std::make_unique<TileFiles>(options.tilesDir, extent, tiles.tileSize,
                                           run.writeOptions(), tiles.cellPositions);
    if (options.memoryLimit)
        return std::make_unique<StreamedTin>(options.output, run.writeOptions(), extent.width,
                                             extent.height, tiles.tileSize,
                                             markOption("memory_limit"));
    return nullptr;
}

// --memory-limit: the tile size within the budget, unless --tile-size gave one (sized once the
// CRS is known: cells that move take more memory a cell), the GDAL cache capped, and a notice.
MemoryBudget planMemory(BuildRun& run, const RefineOptions& refineOptions, TileOptions& tiles,
                        const RefineCrs& crs, bool coordinates) {
    const BuildOptions& options = run.options();
    const std::size_t margin = refineOptions.fillHoles ? 0 : refineOptions.maxHole;
    MemoryBudget budget =
        memoryBudget(*options.memoryLimit, margin, options.tileSize, crs.movesCells());
    tiles.tileSize = budget.tileSize;
    tiles.earlyTileBytes = budget.tileBytes;
    if (coordinates)
        run.notify("tiles of " + std::to_string(budget.tileSize) + " cells a side within " +
                   markOption("memory_limit"));
    return budget;
}

// Tiles (--tile-size): the raster read a tile's window at a time, never whole.
BuildReport buildTiledTin(BuildRun& run) {
    const BuildOptions& options = run.options();
    BuildReport& report = run.report();
    checkOneRasterInput(options);
    io::RasterReadOptions readOptions;
    readOptions.band = options.band;
    io::RasterCells cells(options.inputs.front(), readOptions);
    HeightGrid extent; // the raster's shape, without its cells
    extent.width = cells.width();
    extent.height = cells.height();
    extent.geoTransform = cells.geoTransform();
    const RefineCrs crs = chooseRefineCrs(options, extent.extentCentre(), cells.crsWkt(), report);
    describeCrs(crs.target, report);
    report.rasterCells = extent.cellCount();

    // Reading is part of the refinement: each tile reads its own cells.
    const Stopwatch refineTime;
    const RefineOptions refineOptions = refineOptionsOf(options);
    TileOptions tiles = tileOptionsOf(options);
    if (crs.movesCells()) {
        // A geographic DEM is refined in its UTM zone, each tile at its cells' positions.
        tiles.cellPositions = [source = crs.source, target = crs.target](const HeightGrid& window) {
            return crs::projectCellCentres(window, source, target);
        };
        report.reprojected = true;
    }
    const bool coordinates =
        options.tileDistribution == nullptr || options.tileDistribution->coordinates();
    std::optional<MemoryBudget> budget;
    std::optional<GdalCacheCap> gdalCache;
    if (options.memoryLimit) {
        budget = planMemory(run, refineOptions, tiles, crs, coordinates);
        gdalCache.emplace(budget->gdalCacheBytes);
    }
    run.writeOptions().crsWkt = crs.target;
    const std::unique_ptr<TinSink> sink = tileSink(run, extent, tiles, coordinates);
    if (sink)
        tiles.tileSink = [&](std::size_t tile, TinMesh tin) {
            run.deliver(*sink, tile, std::move(tin), gridCells(extent.width));
        };
    RefineResult result =
        refineTiles(cells, refineOptions, tiles, run.phase(0.0, kReadShare + kTriangulateShare));
    if (!coordinates) {
        report.servedTiles = true;
        return report;
    }
    report.skippedCells = report.rasterCells - result.validCells;
    if (!sink) {
        reportRefinement(result, refineOptions, result.mesh.vertexCount(), report);
        TinProduct product =
            refinedProduct(std::move(result.mesh), extent.width, crs.target, report);
        report.timings.triangulate = refineTime.seconds();
        return run.write(std::move(product));
    }
    reportRefinement(result, refineOptions, sink->points(), report);
    reportTileCounts(sink->points(), sink->triangles(), refineTime, report);
    if (const auto* streamed = dynamic_cast<const StreamedTin*>(sink.get()))
        noticeHeldIndex(*streamed, budget->writerBytes, run);
    return run.close(*sink);
}

// The DEM read whole, its cell counts and reading time in the report.
io::HeightGridRaster readWholeDem(BuildRun& run) {
    const Stopwatch readTime;
    io::RasterReadOptions readOptions;
    readOptions.band = run.options().band;
    io::HeightGridRaster raster =
        io::readHeightGrid(run.options().inputs.front(), readOptions, run.phase(0.0, kReadShare));
    run.report().rasterCells = raster.grid.cellCount();
    run.report().skippedCells = raster.skippedCells;
    run.report().timings.read = readTime.seconds();
    return raster;
}

// The constraints of a simplified DEM before its refinement: their layers in the TIN's CRS,
// and the cells inside replace areas left out of the grid (counted as replaced points).
struct PreparedConstraints {
    ConstraintSources sources;
    std::size_t replacedCells = 0;
};

PreparedConstraints prepareConstraints(std::future<ConstraintLayers>& layers, HeightGrid& grid,
                                       const RefinePlacement& placement,
                                       RefineOptions& refineOptions, BuildRun& run) {
    const Stopwatch constrainTime;
    PreparedConstraints prepared;
    // A projected (geographic) DEM's cells are no longer on its grid: no bilinear z then.
    prepared.sources =
        readConstraintSources(layers.get(), run.options(), placement.targetWkt,
                              placement.positions.empty() ? &grid : nullptr, run.report());
    prepared.replacedCells = leaveOutAreaCells(grid, placement.positions, prepared.sources);
    refineOptions.spareVertices = prepared.sources.spareVertices();
    run.report().timings.constrain = constrainTime.seconds();
    return prepared;
}

} // namespace

TileOptions tileOptionsOf(const BuildOptions& options) {
    TileOptions tiles;
    tiles.tileSize = options.tileSize;
    const RefineOptions& refine = *options.refine;
    tiles.everyCell = !refine.maxError && !refine.maxPoints && !refine.maxTriangles;
    tiles.distribution = options.tileDistribution;
    return tiles;
}

void checkDemOnlyOptions(const BuildOptions& options) {
    if (options.zFactor != 1.0)
        throw InvalidInputError(demOnlyWork(options) + " does not combine with " +
                                markOption("z_factor") + "; scale the DEM first (gdal_calc)");
    const bool tiled = options.memoryLimit || options.tileSize > 0;
    if (tiled && hasConstraints(options))
        throw InvalidInputError(demOnlyWork(options) +
                                " does not combine with breaklines, clip, erase or replace "
                                "polygons yet");
}

BuildReport buildRefinedTin(BuildRun& run) {
    const BuildOptions& options = run.options();
    BuildReport& report = run.report();
    if (options.memoryLimit || options.tileSize > 0)
        return buildTiledTin(run);
    checkOneRasterInput(options);
    // The constraint layers are read while the DEM is.
    std::future<ConstraintLayers> constraintLayers;
    const bool constrained = hasConstraints(options);
    if (constrained)
        constraintLayers = startReadingConstraintLayers(options);
    io::HeightGridRaster raster = readWholeDem(run);
    // A geographic raster is refined in its UTM zone, at its cells' projected positions.
    const RefinePlacement placement =
        placeRefinedCells(options, raster.grid, raster.crsWkt, report);
    describeCrs(placement.targetWkt, report);

    const Stopwatch refineTime;
    RefineOptions refineOptions = refineOptionsOf(options);
    refineOptions.keepHoleTriangles = constrained;
    refineOptions.measure = !constrained; // refineWithConstraints measures every cell
    // With constraints, the refiner has most of the phase and the cells' insertion the rest.
    const double refineShare = constrained ? 0.8 * kTriangulateShare : kTriangulateShare;
    PreparedConstraints prepared;
    if (constrained)
        prepared = prepareConstraints(constraintLayers, raster.grid, placement, refineOptions, run);
    const ProgressCallback refineProgress = run.phase(kReadShare, refineShare);
    RefineResult result =
        placement.positions.empty()
            ? refine(raster.grid, refineOptions, refineProgress)
            : refine(raster.grid, placement.positions, refineOptions, refineProgress);
    reportRefinement(result, refineOptions, result.mesh.vertexCount(), report);
    TinMesh mesh = std::move(result.mesh);
    if (constrained) {
        const Stopwatch constrainTime;
        ConstrainedRefinement corrected = refineWithConstraints(
            raster.grid, placement.positions, std::move(mesh), options, std::move(prepared.sources),
            report, run.phase(kReadShare + refineShare, kTriangulateShare - refineShare));
        mesh = takeConstrainedMesh(std::move(corrected), run);
        report.replacedPoints += prepared.replacedCells;
        report.timings.constrain += constrainTime.seconds();
    }
    const int gridWidth = raster.grid.width;
    raster.grid = {}; // the mesh holds its own vertices
    TinProduct product = refinedProduct(std::move(mesh), gridWidth, placement.targetWkt, report);
    report.timings.triangulate = refineTime.seconds();
    return run.write(std::move(product));
}

} // namespace terratin::detail

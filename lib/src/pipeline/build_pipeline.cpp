#include "terratin/pipeline/build_pipeline.hpp"

#include "../io/tin_stream.hpp"
#include "builds.hpp"
#include "memory_budget.hpp"
#include "terratin/error.hpp"
#include "terratin/pipeline/build_option_table.hpp"

#include <cmath>
#include <optional>
#include <string>
#include <system_error>

namespace terratin {

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
    return writeOptions;
}

namespace {

// The format given, or the output's by its extension (a tile directory's are GeoPackages).
io::TinFormat outputFormat(const BuildOptions& options) {
    if (options.format)
        return *options.format;
    if (!options.tilesDir.empty())
        return io::TinFormat::GeoPackage;
    return io::tinFormatFromPath(options.output);
}

} // namespace

void checkBuildOptions(const BuildOptions& options) {
    checkTriangulationOptions(options.triangulation);
    if (options.refine)
        checkRefineOptions(*options.refine);
    if (options.refine && options.tileSize > 0)
        checkTileOptions(*options.refine, detail::tileOptionsOf(options));
    if (options.keepGeographic && !options.targetSrs.empty())
        throw InvalidInputError(markOption("keep_geographic") + " and " + markOption("t_srs") +
                                " contradict each other");
    if (options.band < 1)
        throw InvalidInputError(markOption("band") + " must be 1 or more");
    if (!std::isfinite(options.zFactor) || options.zFactor == 0.0)
        throw InvalidInputError(markOption("z_factor") + " must be a finite number other than 0");
    if (!options.replaceZField.empty() && options.replace.empty())
        throw InvalidInputError("Build: " + markOption("replace_z_field") + " names the field of " +
                                markOption("replace") + " polygons: give them too");
    if (options.maxEdge && (!std::isfinite(*options.maxEdge) || *options.maxEdge <= 0.0))
        throw InvalidInputError(markOption("max_edge") + " must be a positive number");
    if (options.refine)
        detail::checkDemOnlyOptions(options);
    const bool tilesDir = !options.tilesDir.empty();
    if (tilesDir && !options.memoryLimit && options.tileSize == 0)
        throw InvalidInputError("Build: " + markOption("tiles_dir") + " writes tiles: give " +
                                markOption("tile_size") + " or " + markOption("memory_limit"));
    if (!options.format && options.tilesDir.empty() && options.output.empty())
        return; // no output yet: a caller still filling the options in
    const io::TinWriteOptions writeOptions = tinWriteOptions(options, outputFormat(options));
    io::checkTinWriteOptions(writeOptions);
    if (options.memoryLimit && !tilesDir)
        io::detail::checkTinStreamOptions(writeOptions, markOption("memory_limit"));
}

namespace {

// --memory-limit alone builds a DEM in tiles at full resolution: a DEM's build with no
// simplification. Empty when there is nothing to plan.
std::optional<BuildOptions> planTiles(const BuildOptions& options) {
    if (!options.memoryLimit || options.refine)
        return std::nullopt;
    BuildOptions planned = options;
    planned.refine.emplace(); // the tiles at full resolution, each sized in buildTiledTin
    return planned;
}

BuildReport runBuildStages(const BuildOptions& options, const ProgressCallback& progress) {
    if (const std::optional<BuildOptions> planned = planTiles(options))
        return runBuildStages(*planned, progress);
    detail::BuildRun run(options, outputFormat(options), progress);
    if (options.tilesDir.empty())
        io::checkTinOutput(options.output, run.writeOptions()); // refused now, not after reading
    if (options.tileDistribution != nullptr && !options.memoryLimit && options.tileSize == 0)
        throw InvalidInputError("Build: several processes share the work only by tiles: give " +
                                markOption("tile_size") + " or " + markOption("memory_limit"));
    return options.refine ? detail::buildRefinedTin(run) : detail::buildPointTin(run);
}

// runBuildStages, a thread that cannot start reported as running out of memory.
BuildReport runBuildInMemory(const BuildOptions& options, const ProgressCallback& progress) {
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

} // namespace

BuildReport runBuild(const BuildOptions& options, const ProgressCallback& progress) {
    // The modules below name options by keyword (markOption); the caller's spelling is given
    // to them here, once, on the way out.
    try {
        checkBuildOptions(options);
        return runBuildInMemory(options, progress);
    } catch (Error& error) {
        error.nameOptions(optionNaming(options.optionSpelling));
        throw;
    }
}

} // namespace terratin

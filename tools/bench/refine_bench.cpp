#include "refine_bench.hpp"

#include "terratin/error.hpp"

#ifdef TERRATIN_HAVE_IO
#include "host_scaling.hpp"
#include "host_steal.hpp"
#include "process_memory.hpp"
#include "stats.hpp"

#include "terratin/crs/grid_projection.hpp"
#include "terratin/crs/utm_zone.hpp"
#include "terratin/io/height_grid_reader.hpp"
#include "terratin/refine/refine.hpp"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>
#endif

namespace terratin::bench {

#ifdef TERRATIN_HAVE_IO

namespace {

struct RefineCase {
    const char* label;
    const char* file;
    std::vector<double> tolerances;
    /// Refine a geographic DEM at its cells' positions in its UTM zone, as `terratin build`
    /// does (the reprojection itself is not timed), instead of in its own coordinates.
    bool inUtmZone = false;
};

// The refinement table of docs/benchmarks.md: SRTM3 N44W072 (White Mountains) and Mt Hood
// (UTM 30 m, nodata frame); then the geographic DEMs the way the build refines them: N44W072
// and Everest (voids) in their UTM zones.
const std::vector<RefineCase>& refineCases() {
    static const std::vector<RefineCase> cases = {
        {"N44W072", "srtmpy__N44W072/N44W072.hgt", {1.0, 5.0, 10.0}},
        {"Mt Hood", "gdalraster__lf_elev_220_mt_hood_utm.tif", {1.0, 5.0}},
        {"N44W072 UTM", "srtmpy__N44W072/N44W072.hgt", {5.0}, true},
        {"Everest UTM", "osgearth__mt_everest_90m.tif", {5.0}, true},
    };
    return cases;
}

// The cells' positions in the UTM zone of the DEM's centre, or none.
std::vector<Point2> casePositions(const RefineCase& refineCase,
                                  const io::HeightGridRaster& raster) {
    if (!refineCase.inUtmZone)
        return {};
    const Point2 centre = raster.grid.extentCentre();
    return crs::projectCellCentres(
        raster.grid, raster.crsWkt,
        crs::utmZoneCrs(crs::standardUtmZone(centre.x, centre.y), raster.crsWkt));
}

} // namespace

int runRefineBench(const BenchOptions& options) {
    const std::vector<unsigned> threads =
        options.threadsGiven ? options.threads : std::vector<unsigned>{1, 2};
    if (options.csv)
        std::printf("dem,cells,valid,max_error_m,threads,points,triangles,hole_triangles,"
                    "achieved_max_error_m,rmse_m,seconds,speedup,peak_mib,steal_percent\n");
    else
        std::printf("%-11s %9s %6s %3s %9s %9s %9s %8s %7s %8s %6s %8s %7s\n", "DEM", "cells",
                    "E [m]", "thr", "points", "triangles", "holes", "max err", "RMSE", "time [s]",
                    "speed", "peak MiB", "steal %");
    for (const RefineCase& refineCase : refineCases()) {
        const std::filesystem::path path =
            std::filesystem::path(options.demDirectory) / refineCase.file;
        if (!std::filesystem::exists(path)) {
            std::fprintf(stderr, "terratin-bench: %s not found, skipped\n", path.c_str());
            continue;
        }
        const io::HeightGridRaster raster = io::readHeightGrid(path.string(), {});
        const std::size_t valid = raster.grid.validCount();
        const std::vector<Point2> positions = casePositions(refineCase, raster);
        for (const double tolerance : refineCase.tolerances) {
            std::optional<double> oneThread;
            for (const unsigned threadCount : threads) {
                RefineOptions refineOptions;
                refineOptions.maxError = tolerance;
                refineOptions.threads = threadCount;
                std::vector<double> seconds;
                std::vector<double> peaks;
                RefineResult result;
                PeakMemoryProbe probe;
                HostStealProbe steal;
                steal.start();
                for (unsigned run = 0; run < options.runs; ++run) {
                    probe.start();
                    const Stopwatch stopwatch;
                    result = positions.empty() ? refine(raster.grid, refineOptions)
                                               : refine(raster.grid, positions, refineOptions);
                    seconds.push_back(stopwatch.seconds());
                    if (const std::optional<std::size_t> peak = probe.peakGrowthBytes())
                        peaks.push_back(static_cast<double>(*peak));
                }
                const double time = median(seconds);
                if (!oneThread)
                    oneThread = time;
                const double peakMiB = peaks.empty() ? -1.0 : median(peaks) / (1024.0 * 1024.0);
                // Time the hypervisor gave other guests while this row ran (-1: unknown).
                const double stolen = 100.0 * steal.stolenShare().value_or(-0.01);
                if (options.csv)
                    std::printf("%s,%zu,%zu,%g,%u,%zu,%zu,%zu,%.3f,%.3f,%.4f,%.2f,%.1f,%.1f\n",
                                refineCase.label, raster.grid.cellCount(), valid, tolerance,
                                threadCount, result.mesh.vertexCount(), result.mesh.triangleCount(),
                                result.droppedTriangles, result.maxError, result.rmse, time,
                                *oneThread / time, peakMiB, stolen);
                else
                    std::printf(
                        "%-11s %9zu %6g %3u %9zu %9zu %9zu %8.3f %7.3f %8.3f %6.2f %8.1f %7.1f\n",
                        refineCase.label, raster.grid.cellCount(), tolerance, threadCount,
                        result.mesh.vertexCount(), result.mesh.triangleCount(),
                        result.droppedTriangles, result.maxError, result.rmse, time,
                        *oneThread / time, peakMiB, stolen);
                std::fflush(stdout);
            }
        }
    }
    printHostScaling(options.csv ? stderr : stdout,
                     *std::max_element(threads.begin(), threads.end()));
    return 0;
}

#else

int runRefineBench(const BenchOptions& /*options*/) {
    throw Error("--refine reads DEMs: it needs terratin-bench built with terratin::io "
                "(TERRATIN_BUILD_IO=ON)");
}

#endif

} // namespace terratin::bench

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

// One row: the median of the runs of one case at one tolerance and thread count.
struct RefineRow {
    RefineResult result;
    double seconds = 0.0;
    /// Median growth of the peak resident set, MiB; -1 when unknown.
    double peakMiB = -1.0;
    /// Time the hypervisor gave other guests while the row ran, percent; -1 when unknown.
    double stolenPercent = -1.0;
};

RefineRow measureRefine(const io::HeightGridRaster& raster, const std::vector<Point2>& positions,
                        const RefineOptions& refineOptions, unsigned runs) {
    RefineRow row;
    std::vector<double> seconds;
    std::vector<double> peaks;
    PeakMemoryProbe probe;
    HostStealProbe steal;
    steal.start();
    for (unsigned run = 0; run < runs; ++run) {
        probe.start();
        const Stopwatch stopwatch;
        row.result = positions.empty() ? refine(raster.grid, refineOptions)
                                       : refine(raster.grid, positions, refineOptions);
        seconds.push_back(stopwatch.seconds());
        if (const std::optional<std::size_t> peak = probe.peakGrowthBytes())
            peaks.push_back(static_cast<double>(*peak));
    }
    row.seconds = median(seconds);
    if (!peaks.empty())
        row.peakMiB = median(peaks) / (1024.0 * 1024.0);
    row.stolenPercent = 100.0 * steal.stolenShare().value_or(-0.01);
    return row;
}

void printRefineHeader(bool csv) {
    if (csv)
        std::printf("dem,cells,valid,max_error_m,threads,points,triangles,hole_triangles,"
                    "achieved_max_error_m,rmse_m,seconds,speedup,peak_mib,steal_percent\n");
    else
        std::printf("%-11s %9s %6s %3s %9s %9s %9s %8s %7s %8s %6s %8s %7s\n", "DEM", "cells",
                    "E [m]", "thr", "points", "triangles", "holes", "max err", "RMSE", "time [s]",
                    "speed", "peak MiB", "steal %");
}

// `speedUp`: the case's one-thread seconds (its first row's) / this row's.
void printRefineRow(bool csv, const RefineCase& refineCase, const HeightGrid& grid,
                    std::size_t valid, double tolerance, unsigned threads, const RefineRow& row,
                    double speedUp) {
    const RefineResult& result = row.result;
    if (csv)
        std::printf("%s,%zu,%zu,%g,%u,%zu,%zu,%zu,%.3f,%.3f,%.4f,%.2f,%.1f,%.1f\n",
                    refineCase.label, grid.cellCount(), valid, tolerance, threads,
                    result.mesh.vertexCount(), result.mesh.triangleCount(), result.droppedTriangles,
                    result.maxError, result.rmse, row.seconds, speedUp, row.peakMiB,
                    row.stolenPercent);
    else
        std::printf("%-11s %9zu %6g %3u %9zu %9zu %9zu %8.3f %7.3f %8.3f %6.2f %8.1f %7.1f\n",
                    refineCase.label, grid.cellCount(), tolerance, threads,
                    result.mesh.vertexCount(), result.mesh.triangleCount(), result.droppedTriangles,
                    result.maxError, result.rmse, row.seconds, speedUp, row.peakMiB,
                    row.stolenPercent);
    std::fflush(stdout);
}

} // namespace

int runRefineBench(const BenchOptions& options) {
    const std::vector<unsigned> threads =
        options.threadsGiven ? options.threads : std::vector<unsigned>{1, 2};
    printRefineHeader(options.csv);
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
                const RefineRow row = measureRefine(raster, positions, refineOptions, options.runs);
                if (!oneThread)
                    oneThread = row.seconds;
                printRefineRow(options.csv, refineCase, raster.grid, valid, tolerance, threadCount,
                               row, *oneThread / row.seconds);
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

#include "write_bench.hpp"

#include "terratin/error.hpp"

#ifdef TERRATIN_HAVE_IO
#include "interleaved_runs.hpp"
#include "ogr_write_limits.hpp"
#include "stats.hpp"
#include "write_peers.hpp"

#include "terratin/io/raster_reader.hpp"
#include "terratin/pipeline/build_pipeline.hpp"
#include "terratin/triangulate/triangulate.hpp"

#include <unistd.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>
#endif

namespace terratin::bench {

#ifdef TERRATIN_HAVE_IO

namespace {

namespace fs = std::filesystem;

bool wants(const BenchOptions& options, const std::string& format) {
    return std::find(options.writeFormats.begin(), options.writeFormats.end(), format) !=
           options.writeFormats.end();
}

/// One row of the table: a timed job and what its runs reported.
struct WriteRow {
    std::string label;
    TimedJob job;
    /// terratin runs: the write phase of each run, and the GeoPackage rows / index phases.
    std::vector<double> writeSeconds;
    std::vector<double> rowSeconds;
    std::vector<double> indexSeconds;
    /// terratin runs: everything before the write phase (read, triangulate or refine).
    std::vector<double> beforeWriteSeconds;
    std::uint64_t features = 0;
};

/// A scratch folder for the outputs, removed at the end.
class ScratchDirectory {
public:
    ScratchDirectory()
        : m_path(fs::temp_directory_path() /
                 ("terratin-write-bench-" + std::to_string(::getpid()))) {
        fs::create_directories(m_path);
    }
    ~ScratchDirectory() {
        std::error_code ignored;
        fs::remove_all(m_path, ignored);
    }
    [[nodiscard]] fs::path operator/(const std::string& name) const { return m_path / name; }
    [[nodiscard]] const fs::path& path() const { return m_path; }

private:
    fs::path m_path;
};

/// Adds a row that runs `terratin build` through the library, as the CLI does.
void addTerratinRow(std::vector<WriteRow>& rows, const std::string& label, BuildOptions build) {
    rows.push_back(WriteRow{label, {}, {}, {}, {}, {}, 0});
    const std::size_t index = rows.size() - 1;
    rows[index].job.afterRun = [] {};
    build.overwrite = true;
    rows[index].job.run = [&rows, index, build = std::move(build)] {
        const BuildReport report = runBuild(build);
        WriteRow& row = rows[index];
        row.writeSeconds.push_back(report.timings.write);
        row.rowSeconds.push_back(report.writeRowSeconds);
        row.indexSeconds.push_back(report.writeIndexSeconds);
        row.beforeWriteSeconds.push_back(report.timings.total - report.timings.write);
        row.features = report.writeFeatures;
        return true;
    };
}

void addRow(std::vector<WriteRow>& rows, const std::string& label, std::uint64_t features,
            std::function<void()> run) {
    WriteRow row{label, {}, {}, {}, {}, {}, features};
    row.job.afterRun = [] {};
    row.job.run = [run = std::move(run)] {
        run();
        return true;
    };
    rows.push_back(std::move(row));
}

/// Adds a row whose run times itself: run() returns the seconds that count as its write.
void addMinimalRow(std::vector<WriteRow>& rows, const std::string& label, std::uint64_t features,
                   std::function<double()> run) {
    rows.push_back(WriteRow{label, {}, {}, {}, {}, {}, features});
    const std::size_t index = rows.size() - 1;
    rows[index].job.afterRun = [] {};
    rows[index].job.run = [&rows, index, run = std::move(run)] {
        rows[index].writeSeconds.push_back(run());
        return true;
    };
}

double medianOr(const std::vector<double>& values, double fallback) {
    return values.empty() ? fallback : median(values);
}

/// Prints the rows; "vs script" is the script's time over the row's, "vs bound" the row's time
/// over `boundSeconds` (0: no bound column).
void printTable(const std::string& title, const std::vector<WriteRow>& rows, const WriteRow* script,
                double boundSeconds) {
    std::printf("\n%s\n", title.c_str());
    std::printf("%-28s %8s %8s %7s %7s %12s %8s %9s %9s\n", "run", "total s", "write s", "rows s",
                "index s", "features/s", "peak MiB", "vs script", "vs bound");
    const double scriptSeconds = script != nullptr ? medianOr(script->job.seconds, 0.0) : 0.0;
    for (const WriteRow& row : rows) {
        const double total = medianOr(row.job.seconds, -1.0);
        const double write = medianOr(row.writeSeconds, total);
        const double peakMiB = medianOr(row.job.peakBytes, -1.0 * 1048576.0) / 1048576.0;
        std::printf("%-28s %8.3f %8.3f %7.3f %7.3f %12.0f %8.1f", row.label.c_str(), total, write,
                    medianOr(row.rowSeconds, 0.0), medianOr(row.indexSeconds, 0.0),
                    write > 0.0 ? static_cast<double>(row.features) / write : 0.0, peakMiB);
        if (scriptSeconds > 0.0 && total > 0.0)
            std::printf(" %8.2fx", scriptSeconds / total);
        else
            std::printf(" %9s", "-");
        if (boundSeconds > 0.0 && row.label == "terratin -> .gpkg")
            std::printf(" %8.2fx", total / boundSeconds);
        std::printf("\n");
    }
    if (boundSeconds > 0.0)
        std::printf("bound: terratin's run up to the write, then the SQLite bound = %.3f s "
                    "(medians); 'vs bound' is the GeoPackage run's time over it\n",
                    boundSeconds);
}

double medianSeconds(const WriteRow* row) {
    return row != nullptr ? medianOr(row->job.seconds, 0.0) : 0.0;
}

/// A mesh of separate triangles (three vertices each): enough for the SQLite bound, which
/// stores triangles, not their sharing.
TinMesh meshOfTriangles(const std::vector<std::array<Point3, 3>>& triangles) {
    TinMesh mesh;
    mesh.vertices.resize(3 * triangles.size());
    mesh.triangles.resize(3 * triangles.size());
    for (std::size_t t = 0; t < triangles.size(); ++t)
        for (std::size_t i = 0; i < 3; ++i) {
            mesh.vertices[3 * t + i] = triangles[t][i];
            mesh.triangles[3 * t + i] = static_cast<std::uint32_t>(3 * t + i);
        }
    return mesh;
}

const WriteRow* findRow(const std::vector<WriteRow>& rows, const std::string& label) {
    for (const WriteRow& row : rows)
        if (row.label == label)
            return &row;
    return nullptr;
}

/// "<ours>: write phase N x the <bound>'s": how close a writer comes to GDAL's own bound.
void printWriteRatio(const std::vector<WriteRow>& rows, const std::string& ours,
                     const std::string& bound) {
    const WriteRow* oursRow = findRow(rows, ours);
    const WriteRow* boundRow = findRow(rows, bound);
    if (oursRow == nullptr || boundRow == nullptr || boundRow->writeSeconds.empty())
        return;
    std::printf("%s: write phase %.2fx the %s's\n", ours.c_str(),
                medianOr(oursRow->writeSeconds, 0.0) / medianOr(boundRow->writeSeconds, 1.0),
                bound.c_str());
}

/// Runs the rows' jobs in interleaved rounds (see runInterleaved).
void runRows(std::vector<WriteRow>& rows, const BenchOptions& options) {
    std::vector<TimedJob> jobs;
    for (WriteRow& row : rows)
        jobs.push_back(row.job);
    runInterleaved(jobs, options.runs, options.warmMemory);
    for (std::size_t i = 0; i < rows.size(); ++i)
        rows[i].job = std::move(jobs[i]);
}

void mtHoodTable(const BenchOptions& options, const ScratchDirectory& scratch) {
    const fs::path dem = fs::path(options.demDirectory) / "gdalraster__lf_elev_220_mt_hood_utm.tif";
    if (!fs::exists(dem)) {
        std::fprintf(stderr, "terratin-bench: %s not found, Mt Hood skipped\n", dem.c_str());
        return;
    }
    // Untimed: the mesh the SQLite bound stores.
    const io::RasterPoints raster = io::readRasterPoints(dem.string(), {});
    SqliteLimitPeer limit;
    limit.prepare(triangulate(raster.points).mesh);

    std::vector<WriteRow> rows;
    rows.reserve(16);
    addRow(rows, "read + triangulate", 0, [&] {
        const io::RasterPoints points = io::readRasterPoints(dem.string(), {});
        const TriangulationResult result = triangulate(points.points);
        if (result.mesh.triangleCount() == 0)
            throw Error("no triangles");
    });
    for (const std::string& extension : options.writeFormats) {
        BuildOptions build;
        build.inputs = {dem.string()};
        build.output = scratch / ("hood." + extension);
        addTerratinRow(rows, "terratin -> ." + extension, build);
    }
    if (wants(options, "gpkg"))
        addRow(rows, "SQLite bound (rows + index)", 0,
               [&] { limit.write(scratch / "bound.gpkg"); });
    // The GDAL bounds of the other two OGR formats: plain OGR loops with terratin's fields and
    // options, their attributes computed before their own timer starts (their write column).
    const TinMesh boundMesh = triangulate(raster.points).mesh;
    if (wants(options, "shp"))
        addMinimalRow(rows, "GDAL minimal .shp loop", boundMesh.triangleCount(),
                      [&] { return timeMinimalShapefileWrite(boundMesh, scratch.path()); });
    if (wants(options, "fgb"))
        addMinimalRow(rows, "GDAL minimal .fgb loop", boundMesh.triangleCount(),
                      [&] { return timeMinimalFlatGeobufWrite(boundMesh, scratch.path()); });
    if (scriptPeerBuilt() && wants(options, "gpkg"))
        addRow(rows, "GDAL + CGAL + OGR script", 0, [&] {
            fs::remove(scratch / "script.gpkg");
            runGdalCgalOgrScript(dem.string(), scratch / "script.gpkg");
        });
    runRows(rows, options);
    printTable("Mt Hood, full resolution (" + std::to_string(raster.points.size()) +
                   " points), defaults: all attributes, spatial index",
               rows, findRow(rows, "GDAL + CGAL + OGR script"),
               findRow(rows, "SQLite bound (rows + index)") == nullptr
                   ? 0.0
                   : medianSeconds(findRow(rows, "read + triangulate")) +
                         medianSeconds(findRow(rows, "SQLite bound (rows + index)")));
    printWriteRatio(rows, "terratin -> .shp", "GDAL minimal .shp loop");
    printWriteRatio(rows, "terratin -> .fgb", "GDAL minimal .fgb loop");
}

void n44w072Table(const BenchOptions& options, const ScratchDirectory& scratch) {
    const fs::path dem = fs::path(options.demDirectory) / "srtmpy__N44W072" / "N44W072.hgt";
    if (!fs::exists(dem)) {
        std::fprintf(stderr, "terratin-bench: %s not found, N44W072 skipped\n", dem.c_str());
        return;
    }
    BuildOptions build;
    build.inputs = {dem.string()};
    build.output = scratch / "n44.gpkg";
    build.overwrite = true;
    build.refine = RefineOptions{};
    build.refine->maxError = 1.0;
    // Untimed: the same triangles for the plain OGR loop.
    runBuild(build);
    std::string crsWkt;
    const auto triangles = readTriangles(build.output, &crsWkt);

    SqliteLimitPeer limit;
    limit.prepare(meshOfTriangles(triangles));

    std::vector<WriteRow> rows;
    rows.reserve(3);
    addTerratinRow(rows, "terratin -> .gpkg", build);
    addRow(rows, "plain OGR loop (write only)", triangles.size(), [&] {
        fs::remove(scratch / "loop.gpkg");
        writeWithOgrLoop(triangles, crsWkt, scratch / "loop.gpkg");
    });
    addRow(rows, "SQLite bound (rows + index)", 0, [&] { limit.write(scratch / "bound.gpkg"); });
    runRows(rows, options);
    const double bound = medianOr(rows[0].beforeWriteSeconds, 0.0) + medianSeconds(&rows[2]);
    printTable("N44W072, --max-error 1 (" + std::to_string(triangles.size()) + " triangles)", rows,
               nullptr, bound);
    const double ours = medianOr(rows[0].job.seconds, 0.0);
    const double loop = medianOr(rows[1].job.seconds, 0.0);
    if (ours > 0.0)
        std::printf("terratin end to end is %.2fx faster than the plain OGR loop's write alone\n",
                    loop / ours);
}

} // namespace

int runWriteBench(const BenchOptions& options) {
    const ScratchDirectory scratch;
    mtHoodTable(options, scratch);
    if (wants(options, "gpkg"))
        n44w072Table(options, scratch);
    return 0;
}

#else

int runWriteBench(const BenchOptions& /*options*/) {
    throw Error("--write writes files: it needs terratin-bench built with terratin::io "
                "(TERRATIN_BUILD_IO=ON)");
}

#endif

} // namespace terratin::bench

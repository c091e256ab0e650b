// terratin-bench: how fast terratin triangulates, next to CGAL and GDAL, on the point
// distributions of Kohout & Kolingerova ("Parallel Delaunay triangulation in E2 and E3 for
// computers with shared memory", Parallel Computing 31, 2005; Tables 2-4).
//
// What is measured, for each distribution x size, on one point set generated before any timer,
// in --runs rounds of one run of every configuration and peer (interleaved_runs.hpp):
// - time [s]: median over the runs of the wall-clock time of the triangulation call alone:
//   terratin::triangulate(points, options) (which includes merging duplicates and the BRIO
//   order), CGAL's dt.insert(first, last) (which includes its spatial sort), GDAL's
//   GDALTriangulationCreateDelaunay. Converting points into a peer's input and freeing any
//   result are outside the timer, and so is a touch of as much fresh memory as the previous
//   run used (warmFreeMemory; --no-warm-memory leaves it out): on a virtual machine whose
//   hypervisor takes free memory back, first touches otherwise cost up to a second more in
//   some runs than in others.
// - speed-up: terratin's sequential median / this median, same points.
// - hist B/pt: TriangulationResult::historyBytes / N, the DAG's reserved bytes.
// - mesh B/pt: the capacities of the returned TinMesh's four arrays, in bytes, / N.
// - peak B/pt: median over the runs of how far the process's peak resident set (VmHWM) rose
//   above its resident set just before the call, / N: everything the call touched, result and
//   temporaries (the BRIO order, thread stacks, queues) included, for peers too. Linux only
//   (reset through /proc/self/clear_refs); "n/a" elsewhere.
// - vs CGAL, vs GDAL: terratin's median / the peer's median: below 1 means terratin is faster.
// A peer run longer than --peer-limit seconds is not repeated (its median is of the runs
// made) and the peer is skipped at larger sizes of that distribution; the notes say so.
// Triangle counts are compared across methods and peers; a difference becomes a note.
// The sequential method ignores the thread count and runs once per point set; the batch
// method runs its searchers plus one inserting thread (the "srch" column).

#include "bench_options.hpp"
#include "distributions.hpp"
#include "host_scaling.hpp"
#include "host_steal.hpp"
#include "interleaved_runs.hpp"
#include "peers.hpp"
#include "process_memory.hpp"
#include "refine_bench.hpp"
#include "results_table.hpp"
#include "stats.hpp"
#include "write_bench.hpp"

#include "terratin/error.hpp"
#include "terratin/triangulate/triangulate.hpp"

#include <algorithm>
#include <cstdio>
#include <exception>
#include <memory>
#include <new>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <thread>
#include <utility>
#include <vector>

namespace {

using namespace terratin;
using namespace terratin::bench;

constexpr int kExitOk = 0;
constexpr int kExitError = 1;
constexpr int kExitUsage = 2;

/// A peer, and whether it proved too slow on the current distribution.
struct PeerSlot {
    std::unique_ptr<Peer> peer;
    /// The size at which one of its runs exceeded --peer-limit, or would have by a linear
    /// extrapolation from the last size measured, on this distribution.
    std::optional<std::size_t> tooSlowAt;
    /// The last size measured on this distribution and its median seconds.
    std::size_t lastSize = 0;
    double lastSeconds = 0.0;
};

std::optional<double> perPoint(const std::vector<double>& bytes, std::size_t points) {
    if (bytes.empty())
        return std::nullopt;
    return median(bytes) / static_cast<double>(points);
}

std::size_t meshBytes(const TinMesh& mesh) {
    return mesh.vertices.capacity() * sizeof(Point3) +
           mesh.sourceIndex.capacity() * sizeof(std::uint32_t) +
           mesh.triangles.capacity() * sizeof(std::uint32_t) +
           mesh.neighbours.capacity() * sizeof(std::int32_t);
}

const char* locationName(PointLocation locate) {
    return locate == PointLocation::Dag ? "dag" : "walk";
}

// A job timing terratin with these options; it fills `row` (which must outlive it) as runs
// come back.
TimedJob terratinJob(std::span<const Point3> points, const BenchOptions& bench,
                     const NamedMethod& method, PointLocation locate, unsigned threads,
                     ResultRow& row) {
    TriangulationOptions options;
    options.seed = bench.seed;
    options.order = bench.order;
    options.method = method.method;
    options.locate = locate;
    options.threads = threads;
    options.searchers = bench.searchers;
    options.queueLength = bench.queueLength;
    options.searchersHelpWhenQueueFull = bench.helpWhenFull;
    options.collectDiagnostics = true; // the batch method's searchers and helped locations

    row.points = points.size();
    row.method = method.name;
    // The strip method always walks.
    row.locate = method.method == TriangulationMethod::Strips ? "walk" : locationName(locate);
    row.threadsRequested = threads;
    auto result = std::make_shared<std::optional<TriangulationResult>>();
    TimedJob job;
    job.run = [points, options, result] {
        result->emplace(triangulate(points, options));
        return true;
    };
    job.afterRun = [points, result, &row] {
        const TriangulationResult& done = **result;
        row.threadsUsed = done.threads;
        row.searchers = done.diagnostics->searchers;
        row.helpedLocations = done.diagnostics->helpedLocations;
        row.triangles = done.mesh.triangleCount();
        row.historyBytesPerPoint =
            static_cast<double>(done.historyBytes) / static_cast<double>(points.size());
        row.meshBytesPerPoint =
            static_cast<double>(meshBytes(done.mesh)) / static_cast<double>(points.size());
        result->reset();
    };
    return job;
}

// The runs' median time and peak memory into `row`.
void summarise(const TimedJob& job, std::size_t points, ResultRow& row) {
    row.runs = static_cast<unsigned>(job.seconds.size());
    if (!job.seconds.empty())
        row.seconds = median(job.seconds);
    row.peakBytesPerPoint = perPoint(job.peakBytes, points);
}

std::string groupName(const std::string& distribution, std::size_t points) {
    return distribution + " N=" + std::to_string(points);
}

std::string secondsText(double seconds) {
    char text[32];
    std::snprintf(text, sizeof text, "%.3g s", seconds);
    return text;
}

// A job timing a peer on `points`, or nothing when the peer is skipped (too slow at a smaller
// size of this distribution; `row` and `notes` say so) or cannot take the points. A failed run
// becomes a note and ends the job; `row` and `notes` must outlive it.
std::optional<TimedJob> peerJob(PeerSlot& slot, const std::string& distribution,
                                std::span<const Point3> points, const BenchOptions& bench,
                                ResultRow& row, std::vector<std::string>& notes) {
    Peer& peer = *slot.peer;
    row.distribution = distribution;
    row.points = points.size();
    row.method = peer.name();
    // A peer at least linear in N would overrun the limit at this size: one such run can
    // take many minutes (qhull on the arc), so it is skipped like a slow one.
    if (!slot.tooSlowAt && slot.lastSize > 0 &&
        slot.lastSeconds * static_cast<double>(points.size()) / static_cast<double>(slot.lastSize) >
            bench.peerLimitSeconds)
        slot.tooSlowAt = slot.lastSize;
    if (slot.tooSlowAt) {
        row.unmeasured = "skipped";
        notes.push_back(groupName(distribution, points.size()) + ": " + row.method +
                        " skipped, a run took (or would take) over " +
                        secondsText(bench.peerLimitSeconds) +
                        " at N=" + std::to_string(*slot.tooSlowAt));
        return std::nullopt;
    }
    const auto failed = [&notes, &row, distribution, size = points.size()](const std::string& why) {
        notes.push_back(groupName(distribution, size) + ": " + row.method + ": " + why);
    };
    try {
        peer.prepare(points);
    } catch (const Error& error) {
        failed(error.what());
        return std::nullopt;
    } catch (const std::bad_alloc&) {
        failed("ran out of memory");
        return std::nullopt;
    }
    TimedJob job;
    job.limitSeconds = bench.peerLimitSeconds;
    job.run = [&peer, &row, failed] {
        try {
            row.triangles = peer.triangulate();
            return true;
        } catch (const Error& error) {
            failed(error.what());
        } catch (const std::bad_alloc&) {
            failed("ran out of memory");
        }
        peer.release();
        return false;
    };
    job.afterRun = [&peer] { peer.release(); };
    return job;
}

// After the rounds: the peer's row, and whether it proved too slow for larger sizes.
void finishPeer(PeerSlot& slot, const TimedJob& job, const BenchOptions& bench, ResultRow& row,
                std::vector<std::string>& notes) {
    summarise(job, row.points, row);
    slot.peer->release();
    if (!row.seconds)
        return;
    slot.lastSize = row.points;
    slot.lastSeconds = *row.seconds;
    if (job.seconds.back() > bench.peerLimitSeconds) {
        slot.tooSlowAt = row.points;
        notes.push_back(groupName(row.distribution, row.points) + ": " + row.method + " ran " +
                        std::to_string(row.runs) + " of " + std::to_string(bench.runs) +
                        " runs, the last took " + secondsText(job.seconds.back()) +
                        " (over --peer-limit)");
    }
}

std::optional<double> ratio(const std::optional<double>& numerator,
                            const std::optional<double>& denominator) {
    if (!numerator || !denominator || *denominator <= 0.0)
        return std::nullopt;
    return *numerator / *denominator;
}

struct Configuration {
    NamedMethod method;
    PointLocation locate;
    unsigned threads;
};

// Every run this group's configurations make, per point location: sequential first (the
// speed-ups' reference), then each other method at each thread count. The strip method,
// which always walks, runs once: with the walk rows when there are some, else at the end.
std::vector<Configuration> configurations(const BenchOptions& bench) {
    const bool anyWalk = std::find(bench.locations.begin(), bench.locations.end(),
                                   PointLocation::Walk) != bench.locations.end();
    std::vector<Configuration> runs;
    for (const PointLocation locate : bench.locations) {
        const bool stripsHere =
            anyWalk ? locate == PointLocation::Walk : locate == bench.locations.back();
        for (const NamedMethod& method : bench.methods)
            if (method.method == TriangulationMethod::Sequential)
                runs.push_back({method, locate, 1U});
        for (const NamedMethod& method : bench.methods)
            if (method.method != TriangulationMethod::Sequential &&
                (method.method != TriangulationMethod::Strips || stripsHere))
                for (const unsigned threads : bench.threads)
                    runs.push_back({method, locate, threads});
    }
    return runs;
}

// The seconds of the peer of that name, if it ran.
std::optional<double> peerSeconds(const std::vector<ResultRow>& peerRows,
                                  std::string_view peerName) {
    for (const ResultRow& row : peerRows)
        if (row.method == peerName)
            return row.seconds;
    return std::nullopt;
}

// After the rounds of one group: our rows, with their speed-ups and ratios to the peers,
// then the peers' rows; a triangle count unlike our first row's becomes a note.
void printGroupRows(const std::string& group, const std::vector<Configuration>& ours,
                    std::span<const TimedJob> ourJobs, std::size_t points,
                    std::vector<ResultRow>& rows, const std::vector<ResultRow>& peerRows,
                    ResultTable& table, std::vector<std::string>& notes) {
    std::optional<double> sequentialSeconds;
    std::optional<std::size_t> ourTriangles;
    for (std::size_t c = 0; c < ours.size(); ++c) {
        ResultRow& row = rows[c];
        summarise(ourJobs[c], points, row);
        if (ours[c].method.method == TriangulationMethod::Sequential)
            sequentialSeconds = row.seconds; // rows of one location follow their sequential one
        row.speedUp = ratio(sequentialSeconds, row.seconds);
        row.vsCgal = ratio(row.seconds, peerSeconds(peerRows, "cgal"));
        row.vsGdal = ratio(row.seconds, peerSeconds(peerRows, "gdal"));
        if (!ourTriangles)
            ourTriangles = row.triangles;
        else if (row.triangles != *ourTriangles)
            notes.push_back(group + ": " + row.method + " made " + std::to_string(row.triangles) +
                            " triangles, " + std::to_string(*ourTriangles) + " expected");
        table.printRow(row);
    }
    for (const ResultRow& row : peerRows) {
        if (row.seconds && ourTriangles && row.triangles != *ourTriangles)
            notes.push_back(group + ": " + row.method + " made " + std::to_string(row.triangles) +
                            " triangles, terratin " + std::to_string(*ourTriangles));
        table.printRow(row);
    }
}

// One distribution at one size: every configuration and peer is timed in rounds, one run of
// each per round (interleaved_runs.hpp), and the rows are printed when the rounds are over.
void runGroup(Distribution distribution, std::size_t size, const BenchOptions& bench,
              std::vector<PeerSlot>& peers, ResultTable& table, std::vector<std::string>& notes) {
    const std::vector<Point3> points = generatePoints(distribution, size, bench.seed);
    const std::string name(toString(distribution));
    const std::vector<Configuration> ours = configurations(bench);

    // Jobs hold references to their rows: neither vector may grow once jobs exist.
    std::vector<ResultRow> peerRows(peers.size());
    std::vector<ResultRow> rows(ours.size());
    std::vector<TimedJob> jobs;
    std::vector<std::optional<std::size_t>> peerJobIndex(peers.size());
    for (std::size_t p = 0; p < peers.size(); ++p) {
        if (std::optional<TimedJob> job =
                peerJob(peers[p], name, points, bench, peerRows[p], notes)) {
            peerJobIndex[p] = jobs.size();
            jobs.push_back(std::move(*job));
        }
    }
    const std::size_t firstOurs = jobs.size();
    for (std::size_t c = 0; c < ours.size(); ++c) {
        rows[c].distribution = name;
        jobs.push_back(
            terratinJob(points, bench, ours[c].method, ours[c].locate, ours[c].threads, rows[c]));
    }
    runInterleaved(jobs, bench.runs, bench.warmMemory);

    for (std::size_t p = 0; p < peers.size(); ++p)
        if (peerJobIndex[p])
            finishPeer(peers[p], jobs[*peerJobIndex[p]], bench, peerRows[p], notes);
    printGroupRows(groupName(name, points.size()), ours, std::span(jobs).subspan(firstOurs),
                   points.size(), rows, peerRows, table, notes);
}

std::string orderName(InsertionOrder order) {
    return order == InsertionOrder::Brio ? "brio" : "random";
}

// The peers asked for and built; a line for the preamble about each.
std::vector<PeerSlot> makePeers(const BenchOptions& bench, std::vector<std::string>& preamble) {
    std::vector<PeerSlot> peers;
    const auto add = [&](std::unique_ptr<Peer> peer) {
        preamble.push_back(peer->description());
        peers.push_back({std::move(peer), std::nullopt});
    };
    if (!bench.runCgal)
        preamble.emplace_back("CGAL: skipped (--no-cgal)");
    else if (!cgalBuilt())
        preamble.emplace_back("CGAL: not built");
    else
        add(makeCgalPeer());
    if (!bench.runGdal)
        preamble.emplace_back("GDAL: skipped (--no-gdal)");
    else if (!gdalBuilt())
        preamble.emplace_back("GDAL: not built");
    else if (!gdalHasTriangulation())
        preamble.emplace_back("GDAL: built without qhull, cannot triangulate");
    else
        add(makeGdalPeer());
    return peers;
}

int runBench(const BenchOptions& bench) {
    const Stopwatch total;
    HostStealProbe steal;
    steal.start();
    // The table goes to stdout; in CSV mode the comments go to stderr so stdout stays CSV.
    std::FILE* comments = bench.csv ? stderr : stdout;
    std::vector<std::string> preamble{
        "terratin-bench: median of " + std::to_string(bench.runs) + " runs, " +
        std::to_string(std::thread::hardware_concurrency()) + " hardware threads, order " +
        orderName(bench.order) + ", seed " + std::to_string(bench.seed)};
    std::vector<PeerSlot> peers = makePeers(bench, preamble);
    for (const std::string& line : preamble)
        std::fprintf(comments, "# %s\n", line.c_str());
    if (!bench.csv)
        std::fprintf(stdout, "# speed-up: vs terratin sequential; B/pt: bytes per point; "
                             "vs CGAL/GDAL: terratin time / peer time (<1: terratin faster)\n\n");

    ResultTable table(stdout, bench.csv);
    table.printHeader();
    std::vector<std::string> notes;
    for (std::size_t d = 0; d < bench.distributions.size(); ++d) {
        if (d > 0)
            table.printSeparator();
        for (PeerSlot& slot : peers) {
            slot.tooSlowAt.reset();
            slot.lastSize = 0;
        }
        for (const std::size_t size : bench.sizes)
            runGroup(bench.distributions[d], size, bench, peers, table, notes);
    }

    if (!notes.empty())
        std::fprintf(comments, "\n");
    for (const std::string& note : notes)
        std::fprintf(comments, "# note: %s\n", note.c_str());
    std::fprintf(comments, "# finished in %.1f s\n", total.seconds());
    if (const std::optional<double> stolen = steal.stolenShare())
        std::fprintf(comments,
                     "# host steal: %.1f%% of the CPU time went to other guests of the hypervisor "
                     "(above a few percent, timings and speed-ups are unreliable)\n",
                     100.0 * *stolen);
    if (!bench.threads.empty())
        printHostScaling(comments, *std::max_element(bench.threads.begin(), bench.threads.end()));
    return kExitOk;
}

} // namespace

int main(int argc, char** argv) {
    BenchCommand command;
    try {
        command = parseBenchCommandLine(std::vector<std::string>(argv + 1, argv + argc));
    } catch (const UsageError& error) {
        std::fprintf(stderr, "terratin-bench: %s\n", error.what());
        return kExitUsage;
    }
    if (command.kind == BenchCommand::Kind::Help) {
        std::printf("%s", command.helpText.c_str());
        return kExitOk;
    }
    try {
        if (command.options.refine)
            return runRefineBench(command.options);
        if (command.options.write)
            return runWriteBench(command.options);
        return runBench(command.options);
    } catch (const Error& error) {
        std::fprintf(stderr, "terratin-bench: %s\n", error.what());
    } catch (const std::bad_alloc&) {
        std::fprintf(stderr, "terratin-bench: out of memory\n");
    } catch (const std::exception& error) {
        std::fprintf(stderr, "terratin-bench: unexpected error: %s\n", error.what());
    }
    return kExitError;
}

#include "terratin/triangulate/triangulate.hpp"

#include "../huge_pages.hpp"

#include "../parallel/parallel_for.hpp"
#include "batch_insertion.hpp"
#include "circumcircle_insertion.hpp"
#include "dag_triangulator.hpp"
#include "insertion_order.hpp"
#include "strip_insertion.hpp"

#include "terratin/error.hpp"

#include <algorithm>
#include <chrono>
#include <numeric>
#include <string>
#include <thread>

namespace terratin {

namespace {

using detail::HugePageArray;
using detail::VertexId;

unsigned resolveThreads(unsigned requested) {
    if (requested != 0)
        return requested;
    return std::clamp(std::thread::hardware_concurrency(), 1U, kMaxThreads);
}

// The strip method is the fastest at every size and thread count (it inserts small rounds
// on one thread by itself), but it walks: in a random order, without BRIO's spatial sort, a
// walk crosses O(sqrt n) triangles, so there the DAG's O(log n) descent is the choice.
TriangulationMethod resolveMethod(TriangulationMethod requested, InsertionOrder order) {
    if (requested != TriangulationMethod::Auto)
        return requested;
    return order == InsertionOrder::Brio ? TriangulationMethod::Strips
                                         : TriangulationMethod::Sequential;
}

// The paper found 3 searchers per specialised thread best on two processors for up to
// 100,000 points and 4 above (its Figs. 4-6); with more hardware threads the searchers grow
// with them, since location is the part that scales.
unsigned resolveSearchers(unsigned requested, std::size_t points, unsigned threads) {
    if (requested != 0)
        return requested;
    constexpr std::size_t kLargeInputPoints = 100000;
    const unsigned perTwoThreads = points > kLargeInputPoints ? 4U : 3U;
    return std::clamp(perTwoThreads * threads / 2U, 1U, kMaxThreads - 1);
}

// The points renumbered in insertion order: vertex i is the i-th inserted (vertex 0, the
// auxiliary triangle's finite corner, first). The triangulator reads a point's coordinates
// in every predicate; numbered this way, consecutive insertions read neighbouring memory
// instead of jumping across the whole array.
struct InsertionPlan {
    /// On huge pages (huge_pages.hpp): predicates read older vertices all over the array.
    /// A MeshArray, so that sizing it writes nothing: the threads fill it.
    MeshArray<Point2> local;
    /// preparedIndex[v]: the index in PreparedPoints of vertex v.
    HugePageArray<std::uint32_t> preparedIndex;
    /// Where each BRIO round begins in the order of the vertices after vertex 0 (index 0 is
    /// vertex 1; {0} for a random order: one round).
    std::vector<std::size_t> roundStarts;
};

InsertionPlan planInsertion(std::span<const Point2> local, const TriangulationOptions& options,
                            unsigned threads) {
    const auto count = static_cast<std::uint32_t>(local.size());
    const VertexId highest = detail::DagTriangulator::highestOf(local);
    InsertionPlan plan;
    plan.preparedIndex =
        options.order == InsertionOrder::Brio
            ? detail::brioInsertionOrder(local, highest, options.seed, &plan.roundStarts, threads)
            : detail::randomInsertionOrder(count, highest, options.seed);
    if (plan.roundStarts.empty())
        plan.roundStarts.push_back(0);
    plan.preparedIndex.insert(plan.preparedIndex.begin(), highest);
    plan.local.resize(count);
    detail::parallelFor(count, threads, [&](unsigned, std::size_t begin, std::size_t end) {
        for (std::size_t v = begin; v < end; ++v)
            plan.local[v] = local[plan.preparedIndex[v]];
    });
    return plan;
}

using Clock = std::chrono::steady_clock;

// Seconds since `start`, restarting the clock.
double lap(Clock::time_point& start) {
    const Clock::time_point now = Clock::now();
    const double seconds = std::chrono::duration<double>(now - start).count();
    start = now;
    return seconds;
}

// Inserts with the DAG (sequential, batch or circum-circle) and extracts the mesh. Frees
// plan.local on the way.
void insertWithDag(InsertionPlan& plan, const TriangulationOptions& options, unsigned threads,
                   const ProgressCallback& progress, TriangulationResult& result) {
    Clock::time_point phase = Clock::now();
    const auto count = static_cast<std::uint32_t>(plan.local.size());
    const bool walk = options.locate == PointLocation::Walk;
    detail::DagTriangulator triangulator(plan.local);
    // 1, 2, ..., n-1: every vertex but the auxiliary corner (vertex 0), in insertion order.
    HugePageArray<VertexId> vertices(count - 1);
    std::iota(vertices.begin(), vertices.end(), VertexId{1});
    const std::span<const VertexId> order(vertices);
    MethodDiagnostics diagnostics;
    switch (result.method) {
    case TriangulationMethod::Batch: {
        detail::BatchSettings settings;
        settings.searchers = resolveSearchers(options.searchers, count, threads);
        settings.queueLength = options.queueLength;
        settings.searchersHelpWhenFull = options.searchersHelpWhenQueueFull;
        settings.walk = walk;
        const detail::BatchStatistics statistics =
            detail::insertWithBatchMethod(triangulator, order, settings, progress);
        result.threads = settings.searchers + 1;
        diagnostics.searchers = settings.searchers;
        diagnostics.helpedLocations = statistics.helpedLocations;
        break;
    }
    case TriangulationMethod::Circumcircle: {
        const detail::CircumcircleStatistics statistics = detail::insertWithCircumcircleMethod(
            triangulator, order, plan.roundStarts, threads, walk, progress);
        result.threads = threads;
        diagnostics.waits = statistics.waits;
        diagnostics.overrides = statistics.overrides;
        diagnostics.backOffs = statistics.backOffs;
        diagnostics.deferredEdges = statistics.deferredEdges;
        diagnostics.repairs = statistics.repairs;
        diagnostics.repairFlips = statistics.repairFlips;
        break;
    }
    default: // sequential (its walk keeps no history: see insertWithoutHistory)
        triangulator.insertAll(order, progress);
        result.threads = 1;
        break;
    }
    result.seconds.insert = lap(phase);
    diagnostics.historyNodes = triangulator.nodeCount();
    result.historyBytes = triangulator.memoryBytes();
    if (options.collectDiagnostics)
        result.diagnostics = diagnostics;
    const unsigned extractThreads = result.method == TriangulationMethod::Sequential ? 1 : threads;
    // As in insertWithoutHistory: the extraction reads the DAG alone.
    HugePageArray<VertexId>().swap(vertices);
    HugePageArray<Point2>().swap(plan.local);
    triangulator.extract(result.mesh.triangles, result.mesh.neighbours, extractThreads);
    result.seconds.extract = lap(phase);
}

// Inserts with the history-free Bowyer-Watson core (strip method, or sequential walk) and
// extracts the mesh. Frees plan.local on the way.
void insertWithoutHistory(InsertionPlan& plan, const TriangulationOptions& options,
                          unsigned threads, const ProgressCallback& progress,
                          TriangulationResult& result) {
    Clock::time_point phase = Clock::now();
    // Every vertex, the DAG's auxiliary corner (vertex 0) first: no auxiliary triangle here.
    HugePageArray<VertexId> order(plan.local.size());
    std::iota(order.begin(), order.end(), VertexId{0});
    std::vector<std::size_t> roundStarts{0};
    for (std::size_t r = 1; r < plan.roundStarts.size(); ++r)
        roundStarts.push_back(plan.roundStarts[r] + 1);
    detail::StripTriangulator triangulator(plan.local, threads);
    triangulator.insertAll(order, roundStarts, progress);
    result.seconds.insert = lap(phase);
    result.threads = triangulator.strips();
    result.historyBytes = triangulator.memoryBytes();
    if (options.collectDiagnostics) {
        result.diagnostics.emplace();
        result.diagnostics->deferredPoints = triangulator.deferredPoints();
    }
    // The extraction reads the mesh alone: freed first, the order and the points lend their
    // pages to the output arrays.
    HugePageArray<VertexId>().swap(order);
    HugePageArray<Point2>().swap(plan.local);
    triangulator.extract(result.mesh.triangles, result.mesh.neighbours, threads);
    result.seconds.extract = lap(phase);
}

} // namespace

void checkTriangulationOptions(const TriangulationOptions& options) {
    if (options.threads > kMaxThreads)
        throw InvalidInputError("Triangulator: the thread count must be 0 (all) to " +
                                std::to_string(kMaxThreads) + " (got " +
                                std::to_string(options.threads) + ")");
    if (options.searchers > kMaxThreads - 1)
        throw InvalidInputError("Triangulator: the batch method's searching threads must be 0 "
                                "(automatic) to " +
                                std::to_string(kMaxThreads - 1) + " (got " +
                                std::to_string(options.searchers) + ")");
    if (options.queueLength < 1 || options.queueLength > kMaxQueueLength)
        throw InvalidInputError("Triangulator: the batch method's queue length must be 1 to " +
                                std::to_string(kMaxQueueLength) + " entries (got " +
                                std::to_string(options.queueLength) + ")");
}

const char* toString(TriangulationMethod method) {
    switch (method) {
    case TriangulationMethod::Sequential:
        return "sequential";
    case TriangulationMethod::Batch:
        return "batch";
    case TriangulationMethod::Circumcircle:
        return "circumcircle";
    case TriangulationMethod::Strips:
        return "strips";
    case TriangulationMethod::Auto:
        return "auto";
    }
    return "unknown";
}

TriangulationResult triangulate(std::span<const Point3> points, const TriangulationOptions& options,
                                const ProgressCallback& progress) {
    checkTriangulationOptions(options);
    TriangulationResult result;
    Clock::time_point phase = Clock::now();
    const unsigned threads = resolveThreads(options.threads);
    result.method = resolveMethod(options.method, options.order);
    const bool walk = options.locate == PointLocation::Walk;
    // The sequential method is the baseline of the parallel ones: one thread throughout.
    const unsigned phaseThreads = result.method == TriangulationMethod::Sequential ? 1 : threads;

    PreparedPoints prepared = preparePoints(points, options.duplicateZ, phaseThreads);
    result.seconds.prepare = lap(phase);
    const auto count = static_cast<std::uint32_t>(prepared.local.size());

    InsertionPlan plan = planInsertion(prepared.local, options, phaseThreads);
    // The plan holds the points in insertion order. Freed now, this copy's pages serve the
    // triangulator's first arrays: a fresh page costs a page fault, a freed one is reused.
    HugePageArray<Point2>().swap(prepared.local);
    result.seconds.order = lap(phase);

    reserveRoom(result.mesh, count, options.spareVertices);
    const bool historyFree = result.method == TriangulationMethod::Strips ||
                             (result.method == TriangulationMethod::Sequential && walk);
    if (historyFree)
        insertWithoutHistory(plan, options, phaseThreads, progress, result);
    else
        insertWithDag(plan, options, threads, progress, result);
    result.inputPoints = points.size();
    result.duplicatePoints = prepared.duplicateCount;
    lap(phase); // insertion and extraction timed themselves

    // Vertices carry the caller's exact coordinates (not local + origin, to avoid relying on
    // the round trip) and the elevation chosen by the duplicate policy.
    result.mesh.sourceIndex.resize(count);
    result.mesh.vertices.resize(count);
    detail::parallelFor(count, phaseThreads, [&](unsigned, std::size_t begin, std::size_t end) {
        for (std::size_t v = begin; v < end; ++v) {
            const std::uint32_t preparedIndex = plan.preparedIndex[v];
            const std::uint32_t source = prepared.sourceIndex[preparedIndex];
            result.mesh.sourceIndex[v] = source;
            result.mesh.vertices[v] = {points[source].x, points[source].y,
                                       prepared.z[preparedIndex]};
        }
    });
    result.seconds.extract += lap(phase);
    if (progress)
        progress(1.0, "triangulated");
    return result;
}

} // namespace terratin

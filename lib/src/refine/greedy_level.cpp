// GreedyRefiner: the steps of a level (greedy_refiner.hpp): the scans that find each
// triangle's candidate, the strips' and pairs' tasks on the workers, and the shared step.

#include "greedy_refiner.hpp"

#include "level_schedule.hpp"
#include "level_tasks.hpp"

#include "terratin/error.hpp"

#include <algorithm>
#include <array>
#include <atomic>
#include <vector>

namespace terratin::detail {

namespace {

/// Triangles around a new vertex scanned in one batch.
constexpr std::size_t kMaxFan = 16;

/// A fan of the shared step covering more cells than this is scanned on the workers, in
/// bands of kBandRows rows.
constexpr std::int64_t kParallelScanCells = std::int64_t{1} << 15;
constexpr std::int64_t kBandRows = 32;

/// Insertions between two looks at the cancellation flag (and, on the calling thread, two
/// progress reports).
constexpr std::size_t kCheckEvery = 4096;

} // namespace

PixelCorner GreedyRefiner::corner(VertexId v) const {
    const RefineVertex& vertex = m_vertices[v];
    return {vertex.col, vertex.row, static_cast<double>(vertex.z), v};
}

bool GreedyRefiner::prepareScan(TriId id, TriangleScan& scan) const {
    const MeshTriangle& node = m_mesh->triangle(id);
    return scan.prepare(corner(node.v[0]), corner(node.v[1]), corner(node.v[2]), m_view);
}

std::optional<Candidate> GreedyRefiner::candidateOf(TriId id, const ScanResult& result) const {
    if (result.best < 0.0)
        return std::nullopt; // no valid cell left to insert
    const double priority = result.coversHole ? kHolePriority : result.best;
    if (priority <= m_threshold)
        return std::nullopt;
    return Candidate{priority, static_cast<std::uint32_t>(result.bestCell), id,
                     m_mesh->version(id)};
}

template <class Found>
void GreedyRefiner::scanAll(std::span<const TriId> triangles, Found&& found) const {
    std::array<TriangleScan, kMaxFan> scans;
    std::array<bool, kMaxFan> prepared{};
    for (std::size_t begin = 0; begin < triangles.size(); begin += kMaxFan) {
        const std::size_t count = std::min(kMaxFan, triangles.size() - begin);
        for (std::size_t k = 0; k < count; ++k)
            prepared[k] = prepareScan(triangles[begin + k], scans[k]);
        for (std::size_t k = 0; k < count; ++k)
            if (prepared[k])
                if (const std::optional<Candidate> candidate =
                        candidateOf(triangles[begin + k], scans[k].measure(m_view)))
                    found(*candidate);
    }
}

template <class Found>
void GreedyRefiner::scanOnWorkers(std::span<const TriId> triangles, Found&& found) {
    struct Band {
        std::size_t triangle;
        std::int64_t rowFrom;
        std::int64_t rowTo;
    };
    std::vector<PixelTriangle> pixels;
    std::vector<std::size_t> measured; // index into `triangles` of each pixel triangle
    std::vector<Band> bands;
    for (std::size_t k = 0; k < triangles.size(); ++k) {
        const MeshTriangle& node = m_mesh->triangle(triangles[k]);
        const PixelTriangle pixel(corner(node.v[0]), corner(node.v[1]), corner(node.v[2]));
        if (!pixel.hasArea() || pixel.coversOnlyCorners())
            continue;
        for (std::int64_t row = pixel.rowMin(); row <= pixel.rowMax(); row += kBandRows)
            bands.push_back({pixels.size(), row, std::min(row + kBandRows - 1, pixel.rowMax())});
        pixels.push_back(pixel);
        measured.push_back(k);
    }
    std::vector<ScanResult> results(bands.size());
    std::atomic<std::size_t> next{0};
    m_workers->run([&](unsigned) {
        for (std::size_t b = next++; b < bands.size(); b = next++)
            results[b] =
                measureRows(pixels[bands[b].triangle], m_view, bands[b].rowFrom, bands[b].rowTo);
    });
    // Bands are in row order within each triangle: merging them in order is one scan.
    std::vector<ScanResult> totals(pixels.size());
    for (std::size_t b = 0; b < bands.size(); ++b)
        mergeLater(totals[bands[b].triangle], results[b]);
    for (std::size_t i = 0; i < pixels.size(); ++i)
        if (const std::optional<Candidate> candidate =
                candidateOf(triangles[measured[i]], totals[i]))
            found(*candidate);
}

template <class Found>
void GreedyRefiner::scanFan(std::span<const TriId> triangles, Found&& found) {
    std::int64_t doubleArea = 0;
    for (const TriId t : triangles) {
        const MeshTriangle& node = m_mesh->triangle(t);
        doubleArea +=
            PixelTriangle(corner(node.v[0]), corner(node.v[1]), corner(node.v[2])).doubleArea();
    }
    if (m_workers->size() > 1 && doubleArea > 2 * kParallelScanCells)
        scanOnWorkers(triangles, found);
    else
        scanAll(triangles, found);
}

bool GreedyRefiner::isLive(const Candidate& candidate) const {
    return m_mesh->version(candidate.triangle) == candidate.version &&
           (m_flags[candidate.cell] & kCellVertex) == 0;
}

void GreedyRefiner::scanFirstTriangles() {
    const std::vector<TriId> leaves = m_mesh->slotsInUse();
    std::vector<std::vector<Candidate>> found(m_workers->size());
    std::atomic<std::size_t> next{0};
    m_workers->run([&](unsigned worker) {
        for (std::size_t i = next++; i < leaves.size(); i = next++)
            scanAll(std::span<const TriId>(&leaves[i], 1),
                    [&](const Candidate& candidate) { found[worker].push_back(candidate); });
    });
    for (const std::vector<Candidate>& list : found)
        for (const Candidate& candidate : list)
            route(candidate);
}

void GreedyRefiner::route(const Candidate& candidate) {
    const StripRange strips = m_mesh->strips(candidate.triangle);
    if (strips.single())
        m_strips[strips.first].queue.push(candidate);
    else if (strips.last == strips.first + 1)
        m_strips[strips.first].pairQueue.push(candidate);
    else
        m_shared.push(candidate);
}

int GreedyRefiner::insert(const Candidate& candidate, StripRange allowed,
                          RefineMesh::InsertScratch& scratch, int maxAdded) {
    // The vertex takes the next id of its cell's strip, which only this insertion uses now
    // (the task restricted to strips that include the cell's); the id is kept only if the
    // insertion is done.
    const std::uint32_t cell = candidate.cell;
    Strip& own = m_strips[stripOfCell(cell)];
    const VertexId vertex = own.nextVertex;
    setVertex(vertex, cell);
    const int added =
        m_mesh->tryInsert(vertex, candidate.triangle, allowed, own.region, scratch, maxAdded);
    if (added == 0)
        return 0;
    ++own.nextVertex;
    m_flags[cell] |= kCellVertex;
    return added;
}

void GreedyRefiner::drain(CandidateQueue& queue, StripRange allowed, double level,
                          std::size_t quota, TaskState& task) {
    task.inserted = 0;
    task.triangles = 0;
    task.deferred = 0;
    const LiveTest live{this};
    for (const Candidate* top = queue.top(live);
         top != nullptr && top->priority > level && task.inserted < quota; top = queue.top(live)) {
        const Candidate candidate = queue.pop();
        // The next candidate's triangle and flag are two cache misses at random places:
        // requested now, they arrive while this one is inserted.
        if (const Candidate* next = queue.top(live))
            live.request(*next);
        if (!isLive(candidate))
            continue;
        const int added = insert(candidate, allowed, task.insert, 2);
        if (added == 0) {
            task.refused.push_back({candidate, task.insert.needed});
            ++task.deferred;
            continue;
        }
        ++task.inserted;
        task.triangles += static_cast<std::size_t>(added);
        scanAll(task.insert.fan, [&](const Candidate& found) { route(found); });
        if (task.inserted % kCheckEvery == 0 && m_cancelled.load(std::memory_order_relaxed))
            return;
    }
}

void GreedyRefiner::takeRefusedByStrips(std::uint8_t k) {
    const StripRange pair{k, static_cast<std::uint8_t>(k + 1)};
    for (const std::uint8_t strip : {pair.first, pair.last}) {
        std::vector<Refused>& refused = m_strips[strip].task.refused;
        const auto needsPair = [&](const Refused& r) {
            return r.needed.first == pair.first && r.needed.last == pair.last;
        };
        for (const Refused& r : refused)
            if (needsPair(r))
                m_strips[k].pairQueue.push(r.candidate);
        refused.erase(std::remove_if(refused.begin(), refused.end(), needsPair), refused.end());
    }
}

void GreedyRefiner::queueRefusedInShared() {
    const auto queue = [&](TaskState& task) {
        for (const Refused& r : task.refused)
            m_shared.push(r.candidate);
        task.refused.clear();
    };
    for (Strip& own : m_strips)
        queue(own.task);
    for (TaskState& task : m_pairTasks)
        queue(task);
}

void GreedyRefiner::runStripsAndPairs(double level, std::size_t quota,
                                      const ProgressCallback& progress) {
    std::vector<std::size_t> stripCandidates;
    for (const Strip& own : m_strips)
        stripCandidates.push_back(own.queue.size());
    LevelPlan plan = planLevel(stripCandidates);
    // Only the calling thread reports, with the progress at the start (the counts change
    // while the tasks run).
    const double fraction = nextProgressFraction(level);
    plan.graph.run(*m_workers, m_cancelled, [&](std::size_t graphTask, unsigned worker) {
        const LevelTask task = plan.tasks[graphTask];
        Strip& first = m_strips[task.first()];
        if (task.isPair()) {
            takeRefusedByStrips(task.first());
            drain(first.pairQueue, task.strips(), level, quota, m_pairTasks[task.first()]);
        } else {
            drain(first.queue, task.strips(), level, quota, first.task);
        }
        if (worker == 0 && progress && !progress(fraction, "refining"))
            m_cancelled.store(true, std::memory_order_relaxed);
    });
    if (m_cancelled.load(std::memory_order_relaxed))
        throw Cancelled("Refiner: cancelled");
    for (Strip& own : m_strips) {
        m_triangles += own.task.triangles;
        m_deferred += own.task.deferred;
    }
    for (const TaskState& task : m_pairTasks) {
        m_triangles += task.triangles;
        m_deferred += task.deferred;
        m_pairInsertions += task.inserted;
    }
    queueRefusedInShared();
}

bool GreedyRefiner::runShared(double level, bool exactLimits, const ProgressCallback& progress) {
    if (!exactLimits) {
        runSharedInBatches(level, progress);
        return true;
    }
    std::size_t done = 0;
    const LiveTest live{this};
    for (const Candidate* top = m_shared.top(live); top != nullptr && top->priority > level;
         top = m_shared.top(live)) {
        if (m_options.maxPoints && pointCount() >= *m_options.maxPoints) {
            m_stop = RefineStop::PointLimit;
            return false;
        }
        const Candidate candidate = m_shared.pop();
        if (!isLive(candidate))
            continue;
        const int maxAdded =
            m_options.maxTriangles
                ? static_cast<int>(std::min<std::size_t>(
                      2, *m_options.maxTriangles - std::min(m_triangles, *m_options.maxTriangles)))
                : 2;
        const int added =
            maxAdded > 0 ? insert(candidate, StripRange::all(), m_sharedInsert, maxAdded) : 0;
        if (added == 0) { // only a triangle limit refuses an unrestricted insertion
            m_shared.push(candidate);
            m_stop = RefineStop::TriangleLimit;
            return false;
        }
        ++m_sharedInsertions;
        m_triangles += static_cast<std::size_t>(added);
        scanFan(m_sharedInsert.fan, [&](const Candidate& found) { m_shared.push(found); });
        if (++done % kCheckEvery == 0)
            report(progress, candidate.priority);
    }
    return true;
}

void GreedyRefiner::runSharedInBatches(double level, const ProgressCallback& progress) {
    std::vector<Candidate> batch;
    std::vector<TriId> made;
    const LiveTest live{this};
    const auto aboveLevel = [&] {
        const Candidate* top = m_shared.top(live);
        return top != nullptr && top->priority > level;
    };
    while (aboveLevel()) {
        batch.clear();
        while (aboveLevel())
            batch.push_back(m_shared.pop());
        // Highest first; a candidate whose triangle an earlier one of the batch replaced is
        // dropped: its cells are scanned again with the triangles made.
        made.clear();
        for (const Candidate& candidate : batch) {
            if (!isLive(candidate))
                continue;
            const int added = insert(candidate, StripRange::all(), m_sharedInsert, 2);
            ++m_sharedInsertions;
            m_triangles += static_cast<std::size_t>(added);
            made.insert(made.end(), m_sharedInsert.fan.begin(), m_sharedInsert.fan.end());
        }
        // A cavity reuses its slots, so every slot listed holds a triangle the batch made:
        // each is scanned once, however often the batch rewrote it.
        std::sort(made.begin(), made.end());
        made.erase(std::unique(made.begin(), made.end()), made.end());
        scanFan(made, [&](const Candidate& found) { route(found); });
        report(progress, level);
    }
}

void GreedyRefiner::gatherIntoShared() {
    for (Strip& own : m_strips)
        for (CandidateQueue* queue : {&own.queue, &own.pairQueue})
            while (!queue->empty())
                m_shared.push(queue->pop());
}

} // namespace terratin::detail

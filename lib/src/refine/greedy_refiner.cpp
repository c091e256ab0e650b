#include "greedy_refiner.hpp"

#include "cell_order.hpp"
#include "check_history.hpp"
#include "level_schedule.hpp"
#include "level_tasks.hpp"
#include "located_check.hpp"
#include "stranded_cells.hpp"
#include "valid_hull.hpp"

#include "terratin/error.hpp"
#include "terratin/triangulate/mesh_validation.hpp"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <limits>
#include <string>

namespace terratin::detail {

namespace {

/// Triangles around a new vertex scanned in one batch.
constexpr std::size_t kMaxFan = 16;

/// A fan of the shared step covering more cells than this is scanned on the workers, in
/// bands of kBandRows rows.
constexpr std::int64_t kParallelScanCells = std::int64_t{1} << 15;
constexpr std::int64_t kBandRows = 32;

/// Strips: about this many columns each, at most kMaxStrips. Strips are the unit of parallel
/// work: more of them balance uneven terrain and feed more threads, fewer leave less work to
/// the pairs and to the sequential step (the triangles spanning strips).
constexpr std::int64_t kStripColumns = 128;
constexpr std::size_t kMaxStrips = 32;

/// Insertions between two looks at the cancellation flag (and, on the calling thread, two
/// progress reports).
constexpr std::size_t kCheckEvery = 4096;

} // namespace

GreedyRefiner::GreedyRefiner(const HeightGrid& grid, std::span<const Point2> positions,
                             CellFlags& flags, const RefineOptions& options, RoundWorkers& workers)
    : m_grid(&grid), m_positions(positions), m_flags(flags), m_options(options),
      m_workers(&workers) {
    m_view = {grid.width, grid.height, grid.z.data(), flags.data()};
    m_threshold = options.maxError ? *options.maxError : -1.0;
}

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

void GreedyRefiner::planStrips() {
    // Strips of about equal valid cells.
    const auto width = static_cast<std::size_t>(m_grid->width);
    std::vector<std::size_t> validInColumn(width, 0);
    std::size_t valid = 0;
    // Row by row: a division per cell (cell % width) took longer than the rest of the setup.
    for (std::size_t rowStart = 0; rowStart < m_flags.size(); rowStart += width)
        for (std::size_t col = 0; col < width; ++col)
            validInColumn[col] += (m_flags[rowStart + col] & kCellNoData) == 0 ? 1 : 0;
    for (const std::size_t count : validInColumn)
        valid += count;
    std::size_t count = m_options.strips;
    if (count == 0)
        count = static_cast<std::size_t>(std::max<std::int64_t>(m_grid->width / kStripColumns, 1));
    count = std::clamp<std::size_t>(count, 1, std::min(kMaxStrips, width));
    m_columnStrip.assign(width, 0);
    std::size_t strip = 0;
    std::size_t before = 0; // valid cells left of the current column
    for (std::size_t col = 0; col < width; ++col) {
        // Column col opens strip k + 1 once (k + 1) / count of the valid cells lie to its left.
        while (strip + 1 < count && before * count >= (strip + 1) * valid)
            ++strip;
        m_columnStrip[col] = static_cast<std::uint8_t>(strip);
        before += validInColumn[col];
    }
    m_strips = std::vector<Strip>(strip + 1);
    m_pairTasks = std::vector<TaskState>(m_strips.size() - 1);
    std::vector<std::size_t> validInStrip(m_strips.size(), 0);
    for (std::size_t col = 0; col < width; ++col)
        validInStrip[m_columnStrip[col]] += validInColumn[col];

    // Vertex ids: the hull's, then a range per strip with an id for each of its valid cells.
    // Slots: the hull's region, then one per strip: an insertion adds at most two triangles,
    // from the region of its cell's strip. Reserved storage (huge_pages.hpp): pages are
    // touched only as points are chosen, so memory follows the output.
    std::size_t ids = m_hullPoints;
    std::size_t slots = m_hullPoints;
    for (std::size_t k = 0; k < m_strips.size(); ++k) {
        Strip& own = m_strips[k];
        own.firstVertex = own.nextVertex = static_cast<VertexId>(ids);
        ids += validInStrip[k];
        slots += 2 * validInStrip[k];
    }
    m_vertices = HugePageBuffer<RefineVertex>(ids);
    m_mesh.emplace(std::span<const RefineVertex>(m_vertices.data(), ids), slots);
    m_mesh->addRegion(m_hullPoints);
    for (std::size_t k = 0; k < m_strips.size(); ++k)
        m_strips[k].region = m_mesh->addRegion(2 * validInStrip[k]);
}

void GreedyRefiner::setVertex(VertexId vertex, std::uint32_t cell) {
    // RefineVertex is an implicit-lifetime aggregate: writing into the raw storage is valid.
    const auto width = static_cast<std::uint32_t>(m_grid->width);
    m_vertices[vertex] = {position(cell), static_cast<std::int32_t>(cell % width),
                          static_cast<std::int32_t>(cell / width), m_grid->z[cell],
                          stripOfCell(cell)};
}

void GreedyRefiner::startFromHull() {
    const std::vector<std::uint32_t> hull = validHullCells(*m_grid, m_positions);
    m_hullPoints = hull.size();
    // Every valid cell stays covered, so the hull's corners are the fewest points and
    // (corners - 2) the fewest triangles: a smaller limit could not hold, so it is refused, never
    // exceeded.
    if (m_options.maxPoints && *m_options.maxPoints < hull.size())
        throw InvalidInputError("Refiner: the convex hull of the valid cells has " +
                                std::to_string(hull.size()) +
                                " corners, which every simplified TIN keeps: a point limit of " +
                                std::to_string(*m_options.maxPoints) + " is below that");
    if (m_options.maxTriangles && *m_options.maxTriangles < hull.size() - 2)
        throw InvalidInputError(
            "Refiner: the convex hull of the valid cells has " + std::to_string(hull.size()) +
            " corners, which every simplified TIN keeps, in at least " +
            std::to_string(hull.size() - 2) + " triangles: a triangle limit of " +
            std::to_string(*m_options.maxTriangles) + " is below that");
    planStrips();
    std::vector<VertexId> hullVertices(hull.size());
    for (std::size_t k = 0; k < hull.size(); ++k) {
        hullVertices[k] = static_cast<VertexId>(k);
        setVertex(hullVertices[k], hull[k]);
        m_flags[hull[k]] |= kCellVertex;
    }
    m_mesh->startFromHull(hullVertices, 0);
    m_triangles = hull.size() - 2;
    insertSeedCells();

    // Candidates of the first triangles, scanned in parallel: they cover every valid cell.
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
    m_firstPriority = std::max(highestPriority(), 0.0);
}

void GreedyRefiner::insertSeedCells() {
    // In the order given, each walk starting from the last insertion's triangles: a tile's
    // border cells come side by side. Before any scan, which then sees them all.
    if (m_seedCells.empty())
        return;
    RefineMesh::InsertScratch scratch;
    TriId start = m_mesh->slotsInUse().front();
    for (const std::uint32_t cell : m_seedCells) {
        if ((m_flags[cell] & kCellVertex) != 0)
            continue; // a corner of the hull
        Strip& own = m_strips[stripOfCell(cell)];
        setVertex(own.nextVertex, cell);
        const int added =
            m_mesh->tryInsert(own.nextVertex, start, StripRange::all(), own.region, scratch);
        if (added == 0)
            throw Error("Refiner: seed cell " + std::to_string(cell) + " could not be inserted");
        ++own.nextVertex;
        m_flags[cell] |= kCellVertex;
        m_triangles += static_cast<std::size_t>(added);
        start = scratch.fan.front();
    }
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

double GreedyRefiner::highestPriority() {
    double top = -std::numeric_limits<double>::infinity();
    const LiveTest live{this};
    const auto consider = [&](CandidateQueue& queue) {
        if (const Candidate* first = queue.top(live))
            top = std::max(top, first->priority);
    };
    for (Strip& own : m_strips) {
        consider(own.queue);
        consider(own.pairQueue);
    }
    consider(m_shared);
    return top;
}

std::size_t GreedyRefiner::pointCount() const {
    std::size_t points = m_hullPoints;
    for (const Strip& own : m_strips)
        points += own.nextVertex - own.firstVertex;
    return points;
}

std::size_t GreedyRefiner::budget() const {
    return pointsUnderLimits(m_options.maxPoints, m_options.maxTriangles, pointCount(),
                             m_triangles);
}

double GreedyRefiner::progressFraction(double topPriority) const {
    double fraction = 0.0;
    if (m_options.maxPoints)
        fraction = std::max(fraction, static_cast<double>(pointCount()) /
                                          static_cast<double>(*m_options.maxPoints));
    if (m_options.maxTriangles)
        fraction = std::max(fraction, static_cast<double>(m_triangles) /
                                          static_cast<double>(*m_options.maxTriangles));
    if (m_threshold > 0.0 && std::isfinite(topPriority) && m_firstPriority > m_threshold) {
        // Errors fall roughly geometrically: progress on a log scale from the first to E.
        fraction =
            std::max(fraction, std::log(m_firstPriority / std::max(topPriority, m_threshold)) /
                                   std::log(m_firstPriority / m_threshold));
    }
    return std::clamp(fraction, 0.0, 1.0);
}

double GreedyRefiner::nextProgressFraction(double topPriority) {
    m_reportedFraction = std::max(m_reportedFraction, progressFraction(topPriority));
    return m_reportedFraction;
}

void GreedyRefiner::report(const ProgressCallback& progress, double topPriority) {
    if (progress && !progress(nextProgressFraction(topPriority), "refining")) {
        m_cancelled.store(true, std::memory_order_relaxed);
        throw Cancelled("Refiner: cancelled");
    }
}

void GreedyRefiner::run(const ProgressCallback& progress) {
    startFromHull();
    runLevels(progress);
    if (!m_positions.empty())
        completeAtPositions(progress);
}

void GreedyRefiner::runLevels(const ProgressCallback& progress) {
    for (;;) {
        const double top = highestPriority();
        if (top <= m_threshold)
            return;
        // Past the holes' level (kHolePriority), the errors' scale starts at the highest
        // error: the levels below it and the progress fraction are measured from there.
        if (std::isinf(m_firstPriority) && std::isfinite(top))
            m_firstPriority = top;
        const std::size_t left = budget();
        if (finishesExactly(left, m_strips.size())) {
            // Close to a limit: one thread, global greedy order, exact stop.
            gatherIntoShared();
            runShared(m_threshold, true, progress);
            return;
        }
        const double level = levelBelow(top, m_threshold, m_firstPriority, m_strips.size());
        // The shared step stops exactly if the tasks' quotas would let it go past a limit.
        runStripsAndPairs(level, taskQuota(left, m_strips.size()), progress);
        ++m_levels;
        if (!runShared(level, m_options.maxPoints || m_options.maxTriangles, progress))
            return;
        report(progress, level);
    }
}

void GreedyRefiner::completeAtPositions(const ProgressCallback& progress) {
    // Each check after the first looks only at the cells whose triangle the levels changed.
    CheckHistory history(m_grid->cellCount());
    while (m_stop == RefineStop::ErrorReached) {
        std::vector<TriId> slots; // the slot of each triangle of `mesh`
        const TinMesh mesh = extractInCellOrder(&slots);
        const CheckMemo memo = history.prepare(*m_mesh, slots);
        const std::vector<CellToInsert> cells =
            cellsToInsertAt(mesh, m_view, m_positions, m_threshold, m_workers->size(), &memo);
        history.record(*m_mesh, slots);
        if (cells.empty())
            return;
        // They become candidates like the scans' ones: the levels insert them, rescan what
        // changed and go on until the scans find nothing more.
        ++m_completionPasses;
        for (const CellToInsert& cell : cells) {
            const TriId slot = slots[cell.triangle];
            route(Candidate{cell.priority, cell.cell, slot, m_mesh->version(slot)});
        }
        runLevels(progress);
    }
}

std::vector<std::uint8_t> GreedyRefiner::coverStrandedVertices(TinMesh& mesh,
                                                               std::vector<TriId>& slots,
                                                               std::size_t spareVertices,
                                                               const ProgressCallback& progress) {
    if (std::none_of(m_flags.begin(), m_flags.end(),
                     [](std::uint8_t f) { return (f & kCellOpenHole) != 0; }))
        return {};
    for (;;) {
        std::vector<std::uint8_t> drop = trianglesOverOpenHoles(mesh, m_view, m_workers->size());
        if (m_stop != RefineStop::ErrorReached)
            return drop;
        const std::vector<CellToInsert> cells = cellsBesideStrandedVertices(mesh, drop, m_view);
        if (cells.empty())
            return drop;
        ++m_completionPasses;
        for (const CellToInsert& cell : cells) {
            const TriId slot = slots[cell.triangle];
            route(Candidate{cell.priority, cell.cell, slot, m_mesh->version(slot)});
        }
        runLevels(progress);
        mesh = extractInCellOrder(&slots, spareVertices);
    }
}

TinMesh GreedyRefiner::extractInCellOrder(std::vector<TriId>* slotOfTriangle,
                                          std::size_t spareVertices) const {
    std::vector<VertexRange> ranges{{0, static_cast<VertexId>(m_hullPoints)}};
    for (const Strip& own : m_strips)
        ranges.push_back({own.firstVertex, own.nextVertex});
    return detail::extractInCellOrder(
        *m_mesh, std::span<const RefineVertex>(m_vertices.data(), m_vertices.size()), ranges,
        m_grid->width, m_workers->size(), slotOfTriangle, spareVertices);
}

void checkExactlyDelaunay(const TinMesh& mesh, const std::string& which) {
    const MeshValidation validation = validateDelaunay(mesh);
    if (!validation.ok())
        throw Error("Refiner: " + which + " is not an exact Delaunay triangulation: " +
                    (validation.problems.empty() ? std::string("unknown problem")
                                                 : validation.problems.front()));
}

} // namespace terratin::detail

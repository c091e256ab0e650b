#include "greedy_refiner.hpp"

#include "cell_order.hpp"
#include "check_history.hpp"
#include "level_schedule.hpp"
#include "located_check.hpp"
#include "stranded_cells.hpp"
#include "valid_hull.hpp"

#include "terratin/error.hpp"
#include "terratin/triangulate/mesh_validation.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace terratin::detail {

namespace {

/// Strips: about this many columns each, at most kMaxStrips. Strips are the unit of parallel
/// work: more of them balance uneven terrain and feed more threads, fewer leave less work to
/// the pairs and to the sequential step (the triangles spanning strips).
constexpr std::int64_t kStripColumns = 128;
constexpr std::size_t kMaxStrips = 32;

} // namespace

GreedyRefiner::GreedyRefiner(const HeightGrid& grid, std::span<const Point2> positions,
                             CellFlags& flags, const RefineOptions& options, RoundWorkers& workers)
    : m_grid(&grid), m_positions(positions), m_flags(flags), m_options(options),
      m_workers(&workers) {
    m_view = {grid.width, grid.height, grid.z.data(), flags.data()};
    m_threshold = options.maxError ? *options.maxError : -1.0;
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

    scanFirstTriangles();
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

#include "greedy_refiner.hpp"

#include "located_check.hpp"
#include "valid_hull.hpp"

#include "terratin/error.hpp"
#include "terratin/geometry/predicates.hpp"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <limits>
#include <string>

namespace terratin::detail {

namespace {

constexpr double kHolePriority = std::numeric_limits<double>::infinity();

/// Candidates popped ahead of their stale check (GreedyRefiner::popLive).
constexpr std::size_t kLookAhead = 8;

/// Triangles around a new vertex scanned in one batch.
constexpr std::size_t kMaxFan = 16;

// Progress (and the cancellation check) every this many rounds.
constexpr std::size_t kProgressRounds = 16;

} // namespace

GreedyRefiner::GreedyRefiner(const HeightGrid& grid, std::span<const Point2> positions,
                             CellFlags& flags, const RefineOptions& options,
                             RoundWorkers& workers)
    : m_grid(grid), m_positions(positions), m_flags(flags), m_options(options),
      m_workers(workers) {
    m_view = {grid.width, grid.height, grid.z.data(), flags.data()};
    m_threshold = options.maxError ? *options.maxError : -1.0;
    std::size_t valid = 0;
    for (const std::uint8_t flag : flags)
        valid += (flag & kCellNoData) == 0 ? 1U : 0U;
    m_capacity = valid;
    if (options.maxPoints)
        m_capacity = std::min(m_capacity, *options.maxPoints);
}

PixelCorner GreedyRefiner::corner(VertexId v) const {
    const VertexPixel& pixel = m_vertexPixel[v];
    return {pixel.col, pixel.row, static_cast<double>(pixel.z), v};
}

void GreedyRefiner::addVertex(std::uint32_t cell) {
    const auto width = static_cast<std::uint32_t>(m_grid.width);
    m_vertexCell.push_back(cell);
    m_vertexPixel.push_back({static_cast<std::int32_t>(cell % width),
                             static_cast<std::int32_t>(cell / width), m_grid.z[cell]});
    m_flags[cell] |= kCellVertex;
}

bool GreedyRefiner::mayBeInCircle(const MeshTriangle& node, VertexId vertex) const {
    // Shewchuk's stage A evaluation of the in-circle determinant; anything not certainly
    // negative (outside) counts as inside. The bound is twice the stage A error bound.
    const Point2& d = m_points[vertex];
    const Point2& a = m_points[node.v[0]];
    const Point2& b = m_points[node.v[1]];
    const Point2& c = m_points[node.v[2]];
    const double adx = a.x - d.x;
    const double bdx = b.x - d.x;
    const double cdx = c.x - d.x;
    const double ady = a.y - d.y;
    const double bdy = b.y - d.y;
    const double cdy = c.y - d.y;
    const double bc = bdx * cdy - cdx * bdy;
    const double ca = cdx * ady - adx * cdy;
    const double ab = adx * bdy - bdx * ady;
    const double aLift = adx * adx + ady * ady;
    const double bLift = bdx * bdx + bdy * bdy;
    const double cLift = cdx * cdx + cdy * cdy;
    const double det = aLift * bc + bLift * ca + cLift * ab;
    const double permanent = (std::fabs(bdx * cdy) + std::fabs(cdx * bdy)) * aLift +
                             (std::fabs(cdx * ady) + std::fabs(adx * cdy)) * bLift +
                             (std::fabs(adx * bdy) + std::fabs(bdx * ady)) * cLift;
    return det >= -2.0 * predicates::detail::kIncircleErrorBoundA * permanent;
}

bool GreedyRefiner::prepareScan(TriId id, TriangleScan& scan) const {
    const MeshTriangle& node = m_mesh->triangle(id);
    return scan.prepare(PixelTriangle(corner(node.v[0]), corner(node.v[1]), corner(node.v[2])),
                        m_view);
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

void GreedyRefiner::scanInto(TriId id, std::vector<Candidate>& found) const {
    TriangleScan scan;
    if (!prepareScan(id, scan))
        return;
    if (const std::optional<Candidate> candidate = candidateOf(id, scan.measure(m_view)))
        found.push_back(*candidate);
}

void GreedyRefiner::scanAllInto(std::span<const TriId> triangles,
                                std::vector<Candidate>& found) const {
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
                    found.push_back(*candidate);
    }
}

bool GreedyRefiner::isLive(const Candidate& candidate) const {
    return m_mesh->version(candidate.triangle) == candidate.version &&
           (m_flags[candidate.cell] & kCellVertex) == 0;
}

void GreedyRefiner::popLive(std::size_t count, std::vector<Candidate>& out) {
    // Each check reads the candidate's triangle and flag, two cache misses at random places:
    // candidates are popped kLookAhead ahead of their check and their memory requested then,
    // so the misses overlap. The ones popped but not checked go back.
    std::array<Candidate, kLookAhead> ahead;
    std::size_t head = 0;
    std::size_t size = 0;
    const auto popAhead = [&] {
        const Candidate candidate = m_queue.pop();
        __builtin_prefetch(&m_mesh->triangle(candidate.triangle));
        __builtin_prefetch(&m_flags[candidate.cell]);
        ahead[(head + size++) % kLookAhead] = candidate;
    };
    while (size < kLookAhead && !m_queue.empty())
        popAhead();
    while (out.size() < count && size > 0) {
        const Candidate candidate = ahead[head];
        head = (head + 1) % kLookAhead;
        --size;
        if (!m_queue.empty())
            popAhead();
        if (isLive(candidate))
            out.push_back(candidate);
    }
    for (; size > 0; --size, head = (head + 1) % kLookAhead)
        m_queue.push(ahead[head]);
}

void GreedyRefiner::mergeLive(std::size_t count, std::vector<Candidate>& early,
                              std::vector<Candidate>& out) {
    std::size_t i = 0;
    while (out.size() < count) {
        const bool fromQueue =
            !m_queue.empty() && (i == early.size() || Lower{}(early[i], m_queue.top()));
        if (!fromQueue && i == early.size())
            break;
        const Candidate candidate = fromQueue ? m_queue.pop() : early[i++];
        if (isLive(candidate))
            out.push_back(candidate);
    }
    for (; i < early.size(); ++i)
        m_queue.push(early[i]);
    early.clear();
}

void GreedyRefiner::startFromHull() {
    const std::vector<std::uint32_t> hull = validHullCells(m_grid, m_positions);
    // The hull is kept whatever the point limit. Reserved storage (huge_pages.hpp): pages are
    // touched only as points are chosen, so memory follows the output although the capacity
    // is the worst case. Point2 is an implicit-lifetime aggregate, so writing into the raw
    // storage is valid. A round holds its candidates at ids past the chosen points while it
    // finds their zones.
    m_capacity = std::max(m_capacity, hull.size()) + std::max<std::size_t>(m_options.roundCandidates, 1);
    m_points = HugePageBuffer<Point2>(m_capacity);
    m_vertexCell.reserve(std::min<std::size_t>(m_capacity, std::size_t{1} << 20));
    m_vertexPixel.reserve(m_vertexCell.capacity());
    std::vector<VertexId> hullVertices(hull.size());
    for (std::size_t k = 0; k < hull.size(); ++k) {
        m_points[k] = position(hull[k]);
        addVertex(hull[k]);
        hullVertices[k] = static_cast<VertexId>(k);
    }
    // At most 2n - 2 - h triangles for n points, h of them on the hull.
    m_mesh.emplace(std::span<const Point2>(m_points.data(), m_capacity), 2 * m_capacity,
                   m_workers.size());
    m_mesh->startFromHull(hullVertices);
    m_hullPoints = hull.size();
    m_triangles = hull.size() - 2;

    // Candidates of the first triangles, scanned in parallel: they cover every valid cell.
    std::vector<TriId> leaves;
    for (TriId t = 0; t < m_mesh->slotCount(); ++t)
        if (m_mesh->inUse(t))
            leaves.push_back(t);
    std::vector<WorkerScratch> scratch(m_workers.size());
    std::atomic<std::size_t> next{0};
    m_workers.run([&](unsigned worker) {
        for (std::size_t i = next++; i < leaves.size(); i = next++)
            scanInto(leaves[i], scratch[worker].found);
    });
    for (const WorkerScratch& output : scratch)
        for (const Candidate& candidate : output.found)
            m_queue.push(candidate);
    m_firstPriority = m_queue.empty() ? 0.0 : m_queue.top().priority;
}

void GreedyRefiner::findZone(VertexId vertex, TriId start, Zone& zone) const {
    const RefineMesh& mesh = *m_mesh;
    zone.leaf = mesh.walk(vertex, start);
    // The cavity (the triangles the insertion may replace) first, then the ring around it.
    std::vector<TriId>& nodes = zone.nodes;
    nodes.clear();
    nodes.push_back(zone.leaf);
    zone.growth = 2;
    const int edge = mesh.edgeContaining(zone.leaf, vertex);
    if (edge >= 0) {
        const TriId beyond = mesh.triangle(zone.leaf).n[static_cast<std::size_t>(edge)];
        if (beyond == kNoTriangle)
            zone.growth = 1; // on the hull: one new output triangle
        else
            nodes.push_back(beyond);
    }
    // Breadth-first over the cavity, which stays at the front of `nodes`: the ring members
    // found so far are moved behind each newly found cavity member.
    std::size_t cavityEnd = nodes.size();
    for (std::size_t i = 0; i < cavityEnd; ++i) {
        const MeshTriangle& node = mesh.triangle(nodes[i]);
        for (const TriId n : node.n) {
            if (n == kNoTriangle || std::find(nodes.begin(), nodes.end(), n) != nodes.end())
                continue;
            nodes.push_back(n);
            if (mayBeInCircle(mesh.triangle(n), vertex))
                std::swap(nodes[cavityEnd++], nodes.back());
        }
    }
}

bool GreedyRefiner::claimFree(const Zone& zone, std::uint32_t stamp) const {
    for (const TriId n : zone.nodes)
        if (m_mesh->owner(n) == stamp)
            return false;
    return true;
}

bool GreedyRefiner::claim(const Zone& zone, std::uint32_t stamp) {
    if (!claimFree(zone, stamp))
        return false;
    for (const TriId n : zone.nodes)
        m_mesh->owner(n) = stamp;
    return true;
}

void GreedyRefiner::insert(const Accepted& accepted, WorkerScratch& scratch) {
    // The new triangles are the fan around the point. Its corners' pixels are requested
    // together (they are scattered: vertices are numbered in insertion order, and the flips
    // did not touch them), then its triangles are scanned together (triangle_scan.hpp).
    std::vector<TriId>& fan = scratch.fan;
    fan.clear();
    m_mesh->insert(accepted.vertex, accepted.leaf, scratch.mesh, fan);
    for (const TriId t : fan)
        for (const VertexId v : m_mesh->triangle(t).v)
            __builtin_prefetch(&m_vertexPixel[v]);
    scanAllInto(fan, scratch.found);
}

double GreedyRefiner::progressFraction(double topPriority) const {
    double fraction = 0.0;
    if (m_options.maxPoints)
        fraction = std::max(fraction, static_cast<double>(m_vertexCell.size()) /
                                          static_cast<double>(*m_options.maxPoints));
    if (m_options.maxTriangles)
        fraction = std::max(fraction, static_cast<double>(m_triangles) /
                                          static_cast<double>(*m_options.maxTriangles));
    if (m_threshold > 0.0 && std::isfinite(topPriority) && m_firstPriority > m_threshold) {
        // Errors fall roughly geometrically: progress on a log scale from the first to E.
        fraction = std::max(fraction, std::log(m_firstPriority / std::max(topPriority, m_threshold)) /
                                          std::log(m_firstPriority / m_threshold));
    }
    return std::clamp(fraction, 0.0, 1.0);
}

void GreedyRefiner::run(const ProgressCallback& progress) {
    startFromHull();
    runRounds(progress);
    if (!m_positions.empty())
        completeAtPositions(progress);
}

void GreedyRefiner::runRounds(const ProgressCallback& progress) {
    const std::size_t roundCandidates = std::max<std::size_t>(m_options.roundCandidates, 1);
    std::vector<Accepted> accepted;
    std::vector<Candidate> waiting;
    std::vector<WorkerScratch> scratch(m_workers.size());
    bool limitReached = false;
    std::vector<Candidate> popped;
    // Candidates popped while the previous round inserted (see below), in queue order.
    std::vector<Candidate> early;
    std::vector<Zone> zones(roundCandidates);
    while (!limitReached) {
        // The round's candidates: the first live ones of the early ones merged with the queue,
        // which holds everything the last round found. Then find, in parallel, the triangles
        // each insertion can change (read-only on the mesh); the candidate j sits at vertex id
        // base + j meanwhile.
        accepted.clear();
        waiting.clear();
        popped.clear();
        mergeLive(roundCandidates, early, popped);
        const auto base = static_cast<VertexId>(m_vertexCell.size());
        for (std::size_t j = 0; j < popped.size(); ++j)
            m_points[base + j] = position(popped[j].cell);
        std::atomic<std::size_t> nextZone{0};
        m_workers.run([&](unsigned) {
            for (std::size_t j = nextZone++; j < popped.size(); j = nextZone++)
                findZone(base + static_cast<VertexId>(j), popped[j].triangle, zones[j]);
        });

        // Accept in priority order those whose triangles no earlier one claimed; the accepted
        // points are renumbered base, base + 1, ... (each slot is rewritten only after the
        // candidates before it are done with it).
        const auto stamp = static_cast<std::uint32_t>(m_rounds + 1);
        for (std::size_t j = 0; j < popped.size(); ++j) {
            if (limitReached) {
                waiting.push_back(popped[j]);
                continue;
            }
            if (m_options.maxPoints && m_vertexCell.size() >= *m_options.maxPoints) {
                m_stop = RefineStop::PointLimit;
                limitReached = true;
                waiting.push_back(popped[j]);
                continue;
            }
            const Zone& zone = zones[j];
            if (m_options.maxTriangles &&
                m_triangles + static_cast<std::size_t>(zone.growth) > *m_options.maxTriangles &&
                claimFree(zone, stamp)) {
                m_stop = RefineStop::TriangleLimit;
                limitReached = true;
                waiting.push_back(popped[j]);
                continue;
            }
            if (!claim(zone, stamp)) {
                waiting.push_back(popped[j]);
                continue;
            }
            const auto vertex = static_cast<VertexId>(m_vertexCell.size());
            m_points[vertex] = position(popped[j].cell);
            addVertex(popped[j].cell);
            m_triangles += static_cast<std::size_t>(zone.growth);
            accepted.push_back({vertex, zone.leaf});
        }
        m_deferred += waiting.size();
        if (accepted.empty()) {
            for (const Candidate& c : waiting)
                m_queue.push(c);
            break;
        }

        // Insert: the accepted points are independent; workers take them one by one and keep
        // the candidates they find. Meanwhile the calling thread first pops the next round's
        // likely candidates, the refiner's one sequential job, so that it overlaps the
        // insertions: whatever this round finds and the checks made then are merged in next
        // round by mergeLive, so the rounds are exactly what popping afterwards would give.
        std::atomic<std::size_t> next{0};
        m_workers.run([&](unsigned worker) {
            if (worker == 0 && !limitReached)
                popLive(roundCandidates, early);
            WorkerScratch& own = scratch[worker];
            for (std::size_t i = next++; i < accepted.size(); i = next++)
                insert(accepted[i], own);
        });
        ++m_rounds;
        for (const Candidate& c : waiting)
            m_queue.push(c);
        for (WorkerScratch& own : scratch) {
            for (const Candidate& c : own.found)
                m_queue.push(c);
            own.found.clear();
        }

        if (progress && m_rounds % kProgressRounds == 0) {
            double top = early.empty() ? m_threshold : early.front().priority;
            if (!m_queue.empty())
                top = std::max(top, m_queue.top().priority);
            if (!progress(progressFraction(top), "refining"))
                throw Cancelled("Refiner: cancelled");
        }
    }
}

void GreedyRefiner::completeAtPositions(const ProgressCallback& progress) {
    // Per cell, the slot and version of the triangle that held it at the last check
    // (kNoTriangle: check it again), so that each check after the first looks only at the
    // cells whose triangle the rounds changed (CheckMemo).
    const std::size_t cellCount = m_grid.cellCount();
    std::vector<TriId> cellSlot(cellCount, kNoTriangle);
    std::vector<std::uint32_t> cellVersion(cellCount, 0);
    std::vector<std::uint8_t> unchanged;
    std::vector<std::int32_t> near;
    std::vector<std::int32_t> located(cellCount, -1);
    while (m_stop == RefineStop::ErrorReached) {
        const TinMesh mesh = extract();
        // extract() lists the slots in use in slot order: the slot of each mesh triangle.
        std::vector<TriId> slots;
        slots.reserve(mesh.triangleCount());
        std::vector<std::int32_t> indexOfSlot(m_mesh->slotCount(), -1);
        for (TriId t = 0; t < m_mesh->slotCount(); ++t)
            if (m_mesh->inUse(t)) {
                indexOfSlot[t] = static_cast<std::int32_t>(slots.size());
                slots.push_back(t);
            }
        if (m_completionPasses > 0) {
            unchanged.resize(cellCount);
            near.resize(cellCount);
            for (std::size_t cell = 0; cell < cellCount; ++cell) {
                const TriId slot = cellSlot[cell];
                unchanged[cell] =
                    slot != kNoTriangle && m_mesh->version(slot) == cellVersion[cell] ? 1 : 0;
                near[cell] = slot != kNoTriangle ? indexOfSlot[slot] : -1;
            }
        }
        std::fill(located.begin(), located.end(), -1);
        const CheckMemo memo{unchanged, near, located};
        const std::vector<CellToInsert> cells =
            cellsToInsertAt(mesh, m_view, m_positions, m_threshold, m_workers.size(), &memo);
        for (std::size_t cell = 0; cell < cellCount; ++cell) {
            if (!unchanged.empty() && unchanged[cell] != 0)
                continue;
            cellSlot[cell] = located[cell] >= 0 ? slots[static_cast<std::size_t>(located[cell])]
                                                : kNoTriangle;
            if (cellSlot[cell] != kNoTriangle)
                cellVersion[cell] = m_mesh->version(cellSlot[cell]);
        }
        if (cells.empty())
            return;
        // They become candidates like the scans' ones: the rounds insert them, rescan what
        // changed and go on until the scans find nothing more.
        ++m_completionPasses;
        for (const CellToInsert& cell : cells) {
            const TriId slot = slots[cell.triangle];
            m_queue.push(Candidate{cell.priority, cell.cell, slot, m_mesh->version(slot)});
        }
        runRounds(progress);
    }
}

TinMesh GreedyRefiner::extract() const {
    TinMesh mesh;
    m_mesh->extract(mesh.triangles, mesh.neighbours);
    const std::size_t count = m_vertexCell.size();
    mesh.vertices.resize(count);
    mesh.sourceIndex.resize(count);
    for (std::size_t v = 0; v < count; ++v) {
        const std::uint32_t cell = m_vertexCell[v];
        const Point2& p = m_points[v];
        mesh.vertices[v] = {p.x, p.y, static_cast<double>(m_grid.z[cell])};
        mesh.sourceIndex[v] = cell;
    }
    return mesh;
}

} // namespace terratin::detail

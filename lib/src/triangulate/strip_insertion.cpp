#include "strip_insertion.hpp"

#include "../parallel/parallel_for.hpp"
#include "../parallel/watched_threads.hpp"

#include "terratin/error.hpp"
#include "terratin/geometry/predicates.hpp"

#include <algorithm>
#include <bit>

namespace terratin::detail {

namespace {

// Points of a strip between two checkpoints (see insertAtLevel).
constexpr std::size_t kCheckpointStride = 256;
// Points of a stretch tried for its checkpoint.
constexpr std::size_t kCheckpointTries = 8;
// Points between two progress reports in sequential insertion.
constexpr std::size_t kProgressInterval = std::size_t{1} << 16;

// Strip boundaries at the quantiles of a sample of the x coordinates: strip s holds the
// points with thresholds[s - 1] <= x < thresholds[s].
std::vector<double> stripThresholds(std::span<const Point2> points, unsigned strips) {
    constexpr std::size_t kSampleSize = std::size_t{1} << 16;
    const std::size_t stride = std::max<std::size_t>(1, points.size() / kSampleSize);
    std::vector<double> sample;
    sample.reserve(points.size() / stride + 1);
    for (std::size_t i = 0; i < points.size(); i += stride)
        sample.push_back(points[i].x);
    std::sort(sample.begin(), sample.end());
    std::vector<double> thresholds;
    for (unsigned s = 1; s < strips; ++s)
        thresholds.push_back(sample[sample.size() * s / strips]);
    return thresholds;
}

// The strip of every point (none with one strip).
HugePageArray<std::uint8_t> assignStrips(std::span<const Point2> points,
                                         std::span<const double> thresholds) {
    HugePageArray<std::uint8_t> vertexStrip;
    if (thresholds.empty())
        return vertexStrip;
    vertexStrip.resize(points.size());
    const auto strips = static_cast<unsigned>(thresholds.size() + 1);
    parallelFor(points.size(), strips, [&](unsigned, std::size_t begin, std::size_t end) {
        for (std::size_t v = begin; v < end; ++v)
            vertexStrip[v] = static_cast<std::uint8_t>(
                std::upper_bound(thresholds.begin(), thresholds.end(), points[v].x) -
                thresholds.begin());
    });
    return vertexStrip;
}

// The first triangle and its ghosts.
constexpr std::size_t kStartSlots = 4;

std::size_t slotCapacity(std::size_t points, unsigned strips) {
    return (strips > 1 ? 4 : 2) * points + kStartSlots;
}

} // namespace

StripTriangulator::StripTriangulator(std::span<const Point2> points, unsigned strips,
                                     std::size_t minimumPointsPerStrip)
    : m_strips(std::clamp(strips, 1U, unsigned{kSharedOwner} - 1)),
      m_minimumPointsPerStrip(minimumPointsPerStrip), m_points(points),
      m_thresholds(m_strips > 1 ? stripThresholds(points, m_strips) : std::vector<double>{}),
      m_vertexStrip(assignStrips(points, m_thresholds)),
      m_mesh(points, m_vertexStrip, slotCapacity(points.size(), m_strips)) {
    while (groupsAt(m_topLevel) > 1)
        ++m_topLevel;
    // Each strip gets a region for the triangles of its points (two per point), whatever
    // level inserts them; the unrestricted insertions one for every point.
    if (m_strips > 1) {
        std::vector<std::size_t> stripPoints(m_strips, 0);
        for (const std::uint8_t strip : m_vertexStrip)
            ++stripPoints[strip];
        for (unsigned s = 0; s < m_strips; ++s)
            m_scratch.push_back(m_mesh.makeScratch(2 * stripPoints[s]));
    }
    m_scratch.push_back(m_mesh.makeScratch(2 * points.size() + kStartSlots));
}

void StripTriangulator::insertAll(std::span<const std::uint32_t> order,
                                  std::span<const std::size_t> roundStarts,
                                  const ProgressCallback& progress) {
    if (order.size() < 3)
        throw InvalidInputError("Triangulator: fewer than three points");
    // The first triangle: the first two points and the first point not collinear with them.
    std::size_t third = 2;
    while (third < order.size() && predicates::orient2d(m_points[order[0]], m_points[order[1]],
                                                        m_points[order[third]]) == 0)
        ++third;
    if (third == order.size())
        throw InvalidInputError("Triangulator: all points are collinear");
    m_hint = m_mesh.start(order[0], order[1], order[third], m_scratch.back());

    std::vector<std::size_t> starts(roundStarts.begin(), roundStarts.end());
    starts.push_back(order.size());
    const auto report = [&](std::size_t done) {
        if (progress && !progress(static_cast<double>(done) / static_cast<double>(order.size()),
                                  "triangulating"))
            throw Cancelled("Triangulator: cancelled");
    };
    HugePageArray<std::uint32_t> round;
    for (std::size_t r = 0; r + 1 < starts.size(); ++r) {
        // The round without the first triangle's corners.
        round.clear();
        for (std::size_t i = starts[r]; i < starts[r + 1]; ++i)
            if (i > 1 && i != third)
                round.push_back(order[i]);
        unsigned level = 0;
        while (level < m_topLevel && round.size() < m_minimumPointsPerStrip * groupsAt(level))
            ++level;
        if (level < m_topLevel) {
            insertRoundInGroups(round, level, progress,
                                static_cast<double>(starts[r]) / static_cast<double>(order.size()));
        } else {
            for (std::size_t i = 0; i < round.size(); i += kProgressInterval) {
                const std::size_t end = std::min(round.size(), i + kProgressInterval);
                insertSequentially(std::span(round).subspan(i, end - i));
                report(starts[r] + end);
            }
        }
        report(starts[r + 1]);
    }
    for (CavityMesh::Scratch& scratch : m_scratch)
        m_mesh.closeScratch(scratch);
}

void StripTriangulator::insertSequentially(std::span<const std::uint32_t> points) {
    for (const std::uint32_t p : points)
        m_mesh.insert(p, m_hint, m_scratch.back());
}

template <class Body>
void StripTriangulator::runGroups(unsigned groups, const ProgressCallback& progress,
                                  double fraction, Body&& body) {
    const bool finished = runWatched(
        groups, body, [&] { return !progress || progress(fraction, "triangulating"); },
        [this] { m_stop.store(true, std::memory_order_relaxed); });
    if (!finished)
        throw Cancelled("Triangulator: cancelled");
}

void StripTriangulator::insertRoundInGroups(std::span<const std::uint32_t> round, unsigned level,
                                            const ProgressCallback& progress, double fraction) {
    // queued[l]: the points refused below level l that level l retries, in the order they
    // were refused.
    std::vector<std::vector<std::uint32_t>> queued(m_topLevel + 1);
    const auto insertAndQueueRefused = [&](std::span<const std::uint32_t> points, unsigned l) {
        for (const std::vector<std::uint32_t>& refused :
             insertAtLevel(points, l, progress, fraction))
            for (const std::uint32_t p : refused)
                queued[retryLevel(p, l)].push_back(p);
    };
    insertAndQueueRefused(round, level);
    for (unsigned l = level + 1; l < m_topLevel; ++l) {
        if (queued[l].size() < kMinimumRetriedPoints)
            queued[m_topLevel].insert(queued[m_topLevel].end(), queued[l].begin(), queued[l].end());
        else
            insertAndQueueRefused(queued[l], l);
    }
    m_deferred += queued[m_topLevel].size();
    insertSequentially(queued[m_topLevel]);
}

unsigned StripTriangulator::retryLevel(std::uint32_t point, unsigned level) const {
    // The group's boundaries, in strips: left at `first`, right at `last`.
    const unsigned group = m_vertexStrip[point] >> level;
    const unsigned first = group << level;
    const unsigned last = std::min((group + 1) << level, m_strips);
    unsigned boundary = 0;
    if (first == 0)
        boundary = last;
    else if (last == m_strips)
        boundary = first;
    else
        boundary = m_points[point].x < 0.5 * (m_thresholds[first - 1] + m_thresholds[last - 1])
                       ? first
                       : last;
    if (boundary == 0 || boundary == m_strips)
        return std::min(level + 1, m_topLevel); // a walk cut off, not a boundary
    // Groups at level l have their boundaries at multiples of 2^l: this one is inside a group
    // from the level above its lowest set bit.
    return std::min(static_cast<unsigned>(std::countr_zero(boundary)) + 1, m_topLevel);
}

StripTriangulator::LevelPoints StripTriangulator::groupPoints(std::span<const std::uint32_t> points,
                                                              unsigned level) const {
    const unsigned groups = groupsAt(level);
    LevelPoints grouped;
    grouped.start.assign(groups + 1, 0);
    for (const std::uint32_t p : points)
        ++grouped.start[(m_vertexStrip[p] >> level) + 1];
    for (unsigned g = 0; g < groups; ++g)
        grouped.start[g + 1] += grouped.start[g];
    grouped.points.resize(points.size());
    std::vector<std::size_t> fill(grouped.start.begin(), grouped.start.end() - 1);
    for (const std::uint32_t p : points)
        grouped.points[fill[m_vertexStrip[p] >> level]++] = p;
    return grouped;
}

std::vector<std::vector<CavityTriangleId>>
StripTriangulator::findCheckpoints(const LevelPoints& grouped, unsigned level,
                                   const ProgressCallback& progress, double fraction) {
    const unsigned groups = groupsAt(level);
    std::vector<std::vector<CavityTriangleId>> checkpoints(groups);
    for (unsigned g = 0; g < groups; ++g)
        checkpoints[g].reserve(grouped.size(g) / kCheckpointStride + 1);
    runGroups(groups, progress, fraction, [&](unsigned g) {
        const auto owner = static_cast<std::uint8_t>(g);
        const std::size_t groupEnd = grouped.start[g + 1];
        CavityTriangleId walkStart = m_hint;
        for (std::size_t first = grouped.start[g]; first < groupEnd && !stopping();
             first += kCheckpointStride) {
            // The stretch's first point may lie by a boundary: a few more are tried.
            const std::size_t length = std::min(kCheckpointStride, groupEnd - first);
            const std::size_t tries = std::min(length, kCheckpointTries);
            CavityTriangleId checkpoint = kNoCavityTriangle;
            for (std::size_t k = 0; k < tries && checkpoint == kNoCavityTriangle; ++k) {
                walkStart = m_mesh.locate(grouped.points[first + length * k / tries], walkStart);
                if (m_mesh.mayTouch(walkStart, owner, level))
                    checkpoint = walkStart;
            }
            checkpoints[g].push_back(checkpoint);
        }
    });
    return checkpoints;
}

std::vector<std::vector<std::uint32_t>>
StripTriangulator::insertAtLevel(std::span<const std::uint32_t> points, unsigned level,
                                 const ProgressCallback& progress, double fraction) {
    const unsigned groups = groupsAt(level);
    // The points by group, each group keeping the given (Hilbert) order.
    const LevelPoints grouped = groupPoints(points, level);
    // Checkpoints: for every kCheckpointStride-th point of a group, the triangle holding it
    // before the level starts, if the group may touch it. A thread whose walk is cut off by
    // another group's triangles (its points jump from one cluster to another, or the Hilbert
    // curve enters the group along a boundary) starts again from the checkpoint of the
    // point's stretch instead of giving up on everything after it. The threads find their
    // groups' checkpoints first, all before any thread inserts (the walks read the whole
    // mesh); after that only the group's thread edits the group's triangles, so a checkpoint
    // stays the group's.
    const std::vector<std::vector<CavityTriangleId>> checkpoints =
        findCheckpoints(grouped, level, progress, fraction);
    std::vector<CavityTriangleId> hints(groups, kNoCavityTriangle);
    std::vector<std::vector<std::uint32_t>> refused(groups);
    runGroups(groups, progress, fraction, [&](unsigned g) {
        const auto owner = static_cast<std::uint8_t>(g);
        CavityTriangleId hint = kNoCavityTriangle;
        for (std::size_t i = grouped.start[g]; i < grouped.start[g + 1] && !stopping(); ++i) {
            const std::uint32_t p = grouped.points[i];
            CavityMesh::Scratch& scratch = m_scratch[m_vertexStrip[p]];
            bool inserted =
                hint != kNoCavityTriangle && m_mesh.insert(p, hint, scratch, owner, level);
            const CavityTriangleId checkpoint =
                checkpoints[g][(i - grouped.start[g]) / kCheckpointStride];
            if (!inserted && checkpoint != kNoCavityTriangle && checkpoint != hint) {
                hint = checkpoint;
                inserted = m_mesh.insert(p, hint, scratch, owner, level);
            }
            if (!inserted)
                refused[g].push_back(p);
        }
        hints[g] = hint;
    });
    for (const CavityTriangleId hint : hints)
        if (hint != kNoCavityTriangle)
            m_hint = hint;
    return refused;
}

} // namespace terratin::detail

#include "strip_insertion.hpp"

#include "parallel_for.hpp"

#include "terratin/error.hpp"
#include "terratin/geometry/predicates.hpp"

#include <algorithm>

namespace terratin::detail {

namespace {

// Points of a strip between two checkpoints (see insertRoundInStrips).
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
std::vector<std::uint8_t> assignStrips(std::span<const Point2> points, unsigned strips) {
    std::vector<std::uint8_t> vertexStrip;
    if (strips == 1)
        return vertexStrip;
    const std::vector<double> thresholds = stripThresholds(points, strips);
    vertexStrip.resize(points.size());
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
      m_vertexStrip(assignStrips(points, m_strips)),
      m_mesh(points, m_vertexStrip, slotCapacity(points.size(), m_strips)) {
    // Phase 1 gives each strip a region for the triangles of its points (two per point), the
    // single-threaded insertions one for every point (any point may be deferred).
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
    std::vector<std::uint32_t> round;
    for (std::size_t r = 0; r + 1 < starts.size(); ++r) {
        // The round without the first triangle's corners.
        round.clear();
        for (std::size_t i = starts[r]; i < starts[r + 1]; ++i)
            if (i > 1 && i != third)
                round.push_back(order[i]);
        if (m_strips > 1 && round.size() >= m_minimumPointsPerStrip * m_strips) {
            insertRoundInStrips(round);
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

void StripTriangulator::insertRoundInStrips(std::span<const std::uint32_t> round) {
    // The round's points by strip, each strip keeping the round's (Hilbert) order.
    std::vector<std::size_t> stripStart(m_strips + 1, 0);
    for (const std::uint32_t p : round)
        ++stripStart[m_vertexStrip[p] + 1];
    for (unsigned s = 0; s < m_strips; ++s)
        stripStart[s + 1] += stripStart[s];
    std::vector<std::uint32_t> byStrip(round.size());
    {
        std::vector<std::size_t> fill(stripStart.begin(), stripStart.end() - 1);
        for (const std::uint32_t p : round)
            byStrip[fill[m_vertexStrip[p]]++] = p;
    }
    // Checkpoints: for every kCheckpointStride-th point of a strip, the triangle holding it
    // now if the strip owns it, found before the threads start. A thread whose walk is cut
    // off by another strip's triangles (its points jump from one cluster to another, or the
    // Hilbert curve enters the strip along a boundary) starts again from the checkpoint of
    // the point's stretch instead of deferring everything after it. During phase 1 only
    // the strip's thread edits the strip's triangles, so a checkpoint stays the strip's.
    std::vector<std::vector<CavityTriangleId>> checkpoints(m_strips);
    CavityTriangleId walkStart = m_hint;
    for (unsigned s = 0; s < m_strips; ++s) {
        for (std::size_t first = stripStart[s]; first < stripStart[s + 1];
             first += kCheckpointStride) {
            // The stretch's first point may lie by a boundary: a few more are tried.
            const std::size_t length = std::min(kCheckpointStride, stripStart[s + 1] - first);
            const std::size_t tries = std::min(length, kCheckpointTries);
            CavityTriangleId checkpoint = kNoCavityTriangle;
            for (std::size_t k = 0; k < tries && checkpoint == kNoCavityTriangle; ++k) {
                walkStart = m_mesh.locate(byStrip[first + length * k / tries], walkStart);
                if (m_mesh.ownerOf(walkStart) == s)
                    checkpoint = walkStart;
            }
            checkpoints[s].push_back(checkpoint);
        }
    }
    std::vector<CavityTriangleId> hints(m_strips, kNoCavityTriangle);
    std::vector<std::vector<std::uint32_t>> deferred(m_strips);
    runOnThreads(m_strips, [&](unsigned s) {
        const auto owner = static_cast<std::uint8_t>(s);
        CavityTriangleId hint = kNoCavityTriangle;
        for (std::size_t i = stripStart[s]; i < stripStart[s + 1]; ++i) {
            const std::uint32_t p = byStrip[i];
            bool inserted =
                hint != kNoCavityTriangle && m_mesh.insert(p, hint, m_scratch[s], owner);
            const CavityTriangleId checkpoint =
                checkpoints[s][(i - stripStart[s]) / kCheckpointStride];
            if (!inserted && checkpoint != kNoCavityTriangle && checkpoint != hint) {
                hint = checkpoint;
                inserted = m_mesh.insert(p, hint, m_scratch[s], owner);
            }
            if (!inserted)
                deferred[s].push_back(p);
        }
        hints[s] = hint;
    });
    for (unsigned s = 0; s < m_strips; ++s) {
        if (hints[s] != kNoCavityTriangle)
            m_hint = hints[s];
        m_deferred += deferred[s].size();
        insertSequentially(deferred[s]);
    }
}

} // namespace terratin::detail

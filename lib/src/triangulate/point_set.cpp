#include "terratin/triangulate/point_set.hpp"

#include "terratin/error.hpp"
#include "terratin/geometry/predicates.hpp"

#include "../number_text.hpp"
#include "../parallel/parallel_for.hpp"
#include "box.hpp"
#include "distinct_points.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <span>
#include <string>
#include <utility>
#include <vector>

namespace terratin {

using terratin::detail::numberText;

namespace {

using detail::Box;

// Vertex ids are 32-bit and the triangulator reserves ids for its two symbolic vertices and a
// "none" marker, so the input must leave room for them.
constexpr std::size_t kMaxPoints = std::numeric_limits<std::uint32_t>::max() - 4;

bool isFinite(const Point3& p) {
    return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z);
}

void checkFinite(std::span<const Point3> points, unsigned threads) {
    std::atomic<bool> allFinite{true};
    detail::parallelFor(points.size(), threads, [&](unsigned, std::size_t begin, std::size_t end) {
        if (!std::all_of(points.begin() + begin, points.begin() + end, isFinite))
            allFinite.store(false, std::memory_order_relaxed);
    });
    if (allFinite.load(std::memory_order_relaxed))
        return;
    // The first offender, for the message.
    const auto first = std::find_if_not(points.begin(), points.end(), isFinite);
    throw InvalidInputError("Triangulator: point " + std::to_string(first - points.begin()) +
                            " has a non-finite coordinate or elevation");
}

// Folds each duplicate's elevation (and, for Last, its index) into the prepared entry of its
// first occurrence. Duplicates come by ascending input index, so "last" and the order of the
// sums do not depend on the thread count.
void mergeDuplicates(std::span<const Point3> points,
                     const std::vector<detail::DuplicatePoint>& duplicates, DuplicateZPolicy policy,
                     PreparedPoints& prepared) {
    // The first occurrences are sorted, so a binary search finds each group's position; all
    // are found before the Last policy changes sourceIndex.
    std::vector<std::size_t> groupOf(duplicates.size());
    for (std::size_t d = 0; d < duplicates.size(); ++d)
        groupOf[d] = static_cast<std::size_t>(std::lower_bound(prepared.sourceIndex.begin(),
                                                               prepared.sourceIndex.end(),
                                                               duplicates[d].first) -
                                              prepared.sourceIndex.begin());
    std::vector<std::uint32_t> groupSize;
    if (policy == DuplicateZPolicy::Mean)
        groupSize.assign(prepared.sourceIndex.size(), 1);
    for (std::size_t d = 0; d < duplicates.size(); ++d) {
        const detail::DuplicatePoint& duplicate = duplicates[d];
        const std::size_t k = groupOf[d];
        const double z = points[duplicate.index].z;
        switch (policy) {
        case DuplicateZPolicy::First:
            break;
        case DuplicateZPolicy::Last:
            prepared.sourceIndex[k] = duplicate.index;
            prepared.z[k] = z;
            break;
        case DuplicateZPolicy::Min:
            prepared.z[k] = std::min(prepared.z[k], z);
            break;
        case DuplicateZPolicy::Max:
            prepared.z[k] = std::max(prepared.z[k], z);
            break;
        case DuplicateZPolicy::Mean:
            prepared.z[k] += z;
            ++groupSize[k];
            break;
        }
    }
    if (policy == DuplicateZPolicy::Mean)
        for (std::size_t k = 0; k < groupSize.size(); ++k)
            prepared.z[k] /= static_cast<double>(groupSize[k]);
}

// True when value - origin is exactly representable (Knuth's TwoDiff error term is zero).
bool subtractsExactly(double value, double origin) {
    const double difference = value - origin;
    const double originVirtual = value - difference;
    const double valueVirtual = difference + originVirtual;
    const double error = (value - valueVirtual) + (originVirtual - origin);
    return error == 0.0;
}

// Centre of [lo, hi] rounded to a multiple of the ulp of the largest magnitude in the range, so
// that it is a multiple of every input's ulp: then x - origin is exact whenever it is not
// larger than x itself, which holds for data far from zero (UTM coordinates, say).
double roundedCentre(double lo, double hi) {
    const double centre = lo + (hi - lo) / 2.0;
    const double largest = std::max(std::abs(lo), std::abs(hi));
    if (largest == 0.0)
        return 0.0;
    const double ulp = std::nextafter(largest, std::numeric_limits<double>::infinity()) - largest;
    return std::round(centre / ulp) * ulp;
}

Point2 chooseOrigin(std::span<const Point3> points, std::span<const std::uint32_t> distinct,
                    unsigned threads) {
    std::vector<Box> boxes(detail::parallelForThreads(distinct.size(), threads));
    detail::parallelFor(distinct.size(), threads,
                        [&](unsigned block, std::size_t begin, std::size_t end) {
                            Box box; // local: the blocks' boxes share a cache line
                            for (std::size_t k = begin; k < end; ++k)
                                box.add(points[distinct[k]]);
                            boxes[block] = box;
                        });
    Box all;
    for (const Box& box : boxes)
        all.add(box);
    const Point2 centre{roundedCentre(all.minX, all.maxX), roundedCentre(all.minY, all.maxY)};
    std::atomic<bool> exactX{true};
    std::atomic<bool> exactY{true};
    detail::parallelFor(distinct.size(), threads,
                        [&](unsigned, std::size_t begin, std::size_t end) {
                            bool x = true;
                            bool y = true;
                            for (std::size_t k = begin; k < end; ++k) {
                                x = x && subtractsExactly(points[distinct[k]].x, centre.x);
                                y = y && subtractsExactly(points[distinct[k]].y, centre.y);
                            }
                            if (!x)
                                exactX.store(false, std::memory_order_relaxed);
                            if (!y)
                                exactY.store(false, std::memory_order_relaxed);
                        });
    return {exactX.load(std::memory_order_relaxed) ? centre.x : 0.0,
            exactY.load(std::memory_order_relaxed) ? centre.y : 0.0};
}

// The exact predicates' range (predicates.hpp): beyond it their products could overflow or
// underflow and the sign would no longer be exact.
constexpr double kSmallestCoordinate = 1e-60;
constexpr double kLargestCoordinate = 1e70;

// `local` are the distinct points less `origin`; the message gives the input's own value, which
// local + origin restores exactly (chooseOrigin takes an origin only when the subtraction is).
void requirePredicateRange(std::span<const Point2> local, Point2 origin, unsigned threads) {
    const auto outside = [](double value) {
        const double magnitude = std::abs(value);
        return magnitude != 0.0 &&
               (magnitude < kSmallestCoordinate || magnitude > kLargestCoordinate);
    };
    std::atomic<bool> inRange{true};
    detail::parallelFor(local.size(), threads, [&](unsigned, std::size_t begin, std::size_t end) {
        for (std::size_t i = begin; i < end; ++i)
            if (outside(local[i].x) || outside(local[i].y))
                inRange.store(false, std::memory_order_relaxed);
    });
    if (inRange.load(std::memory_order_relaxed))
        return;
    // The first offender, for the message.
    for (const Point2& p : local)
        if (outside(p.x) || outside(p.y))
            throw InvalidInputError("Triangulator: point (" + numberText(p.x + origin.x) + ", " +
                                    numberText(p.y + origin.y) +
                                    ") is out of range: each coordinate" +
                                    (origin.x != 0.0 || origin.y != 0.0
                                         ? ", less the data's centre (" + numberText(origin.x) +
                                               ", " + numberText(origin.y) + "),"
                                         : std::string()) +
                                    " must be 0 or of magnitude 1e-60 .. 1e70");
}

void requireTwoDimensions(std::span<const Point2> local) {
    if (local.size() >= 3) {
        const Point2& a = local[0];
        const Point2& b = local[1];
        for (std::size_t i = 2; i < local.size(); ++i)
            if (predicates::orient2d(a, b, local[i]) != 0.0)
                return;
    }
    throw InvalidInputError("Triangulator: need at least three distinct points that are not all "
                            "on one line (got " +
                            std::to_string(local.size()) + " distinct points" +
                            (local.size() >= 3 ? ", all collinear)" : ")"));
}

} // namespace

PreparedPoints preparePoints(std::span<const Point3> points, DuplicateZPolicy policy,
                             unsigned threads) {
    if (points.size() > kMaxPoints)
        throw InvalidInputError("Triangulator: too many points (" + std::to_string(points.size()) +
                                "); at most " + std::to_string(kMaxPoints) + " are supported");
    checkFinite(points, threads);

    detail::DistinctPoints distinct = detail::findDistinctPoints(points, threads);
    PreparedPoints prepared;
    prepared.duplicateCount = distinct.duplicates.size();
    prepared.sourceIndex = std::move(distinct.firstOccurrences);
    prepared.z.resize(prepared.sourceIndex.size());
    detail::parallelFor(prepared.z.size(), threads,
                        [&](unsigned, std::size_t begin, std::size_t end) {
                            for (std::size_t k = begin; k < end; ++k)
                                prepared.z[k] = points[prepared.sourceIndex[k]].z;
                        });
    mergeDuplicates(points, distinct.duplicates, policy, prepared);
    prepared.origin = chooseOrigin(points, prepared.sourceIndex, threads);
    prepared.local.resize(prepared.sourceIndex.size());
    detail::parallelFor(
        prepared.local.size(), threads, [&](unsigned, std::size_t begin, std::size_t end) {
            for (std::size_t k = begin; k < end; ++k) {
                const Point3& p = points[prepared.sourceIndex[k]];
                prepared.local[k] = {p.x - prepared.origin.x, p.y - prepared.origin.y};
            }
        });

    requirePredicateRange(prepared.local, prepared.origin, threads);
    requireTwoDimensions(prepared.local);
    return prepared;
}

} // namespace terratin

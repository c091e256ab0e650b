#include "terratin/triangulate/point_set.hpp"

#include "terratin/error.hpp"
#include "terratin/geometry/predicates.hpp"

#include "parallel_for.hpp"

#include <algorithm>
#include <array>
#include <atomic>
#include <bit>
#include <cmath>
#include <limits>
#include <string>

namespace terratin {

namespace {

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

// A distinct (x, y) and what its duplicates contributed so far.
struct Survivor {
    std::uint32_t firstIndex;
    std::uint32_t source;
    double z;
    std::uint32_t count;
};

void mergeDuplicate(Survivor& survivor, std::uint32_t index, double z, DuplicateZPolicy policy) {
    ++survivor.count;
    switch (policy) {
    case DuplicateZPolicy::First:
        break;
    case DuplicateZPolicy::Last:
        survivor.source = index;
        survivor.z = z;
        break;
    case DuplicateZPolicy::Min:
        survivor.z = std::min(survivor.z, z);
        break;
    case DuplicateZPolicy::Max:
        survivor.z = std::max(survivor.z, z);
        break;
    case DuplicateZPolicy::Mean:
        survivor.z += z; // divided by the count once the group is complete
        break;
    }
}

// Bits of a coordinate with -0 folded onto +0, so that equal doubles hash equally.
std::uint64_t coordinateBits(double value) {
    return std::bit_cast<std::uint64_t>(value == 0.0 ? 0.0 : value);
}

std::uint64_t positionHash(const Point3& p) {
    // A multiply-xorshift mix (the finaliser of splitmix64) of both coordinates: cheap and
    // spreads grid coordinates, whose low mantissa bits are all zero, over the whole table.
    std::uint64_t h = coordinateBits(p.x) * 0x9E3779B97F4A7C15ULL ^ coordinateBits(p.y);
    h = (h ^ (h >> 30U)) * 0xBF58476D1CE4E5B9ULL;
    h = (h ^ (h >> 27U)) * 0x94D049BB133111EBULL;
    return h ^ (h >> 31U);
}

// One survivor per distinct (x, y), in order of first occurrence, found with an
// open-addressing hash table: O(n) expected, where sorting the points would cost O(n log n).
std::vector<Survivor> mergeDuplicates(std::span<const Point3> points, DuplicateZPolicy policy) {
    constexpr std::uint32_t kEmpty = std::numeric_limits<std::uint32_t>::max();
    // At most half full, so probe sequences stay short.
    const std::size_t capacity = std::bit_ceil(std::max<std::size_t>(2 * points.size(), 16));
    std::vector<std::uint32_t> table(capacity, kEmpty);
    std::vector<Survivor> survivors;
    survivors.reserve(points.size());
    // Each point's first probe is a cache miss in a table of several megabytes: the slots of
    // the next kLookAhead points are computed and prefetched ahead of their turn.
    constexpr std::size_t kLookAhead = 16;
    std::array<std::size_t, kLookAhead> ahead{};
    const auto home = [&](std::size_t i) { return positionHash(points[i]) & (capacity - 1); };
    for (std::size_t i = 0; i < std::min(kLookAhead, points.size()); ++i) {
        ahead[i] = home(i);
        __builtin_prefetch(&table[ahead[i]]);
    }
    for (std::uint32_t i = 0; i < points.size(); ++i) {
        const Point3& p = points[i];
        std::size_t slot = ahead[i % kLookAhead];
        if (i + kLookAhead < points.size()) {
            ahead[i % kLookAhead] = home(i + kLookAhead);
            __builtin_prefetch(&table[ahead[i % kLookAhead]]);
        }
        for (;;) {
            const std::uint32_t existing = table[slot];
            if (existing == kEmpty) {
                table[slot] = static_cast<std::uint32_t>(survivors.size());
                survivors.push_back({i, i, p.z, 1});
                break;
            }
            const Point3& q = points[survivors[existing].firstIndex];
            if (q.x == p.x && q.y == p.y) {
                mergeDuplicate(survivors[existing], i, p.z, policy);
                break;
            }
            slot = (slot + 1) & (capacity - 1);
        }
    }
    if (policy == DuplicateZPolicy::Mean)
        for (Survivor& survivor : survivors)
            survivor.z /= static_cast<double>(survivor.count);
    return survivors;
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

// The bounding box of some points.
struct Box {
    double minX = std::numeric_limits<double>::infinity();
    double minY = std::numeric_limits<double>::infinity();
    double maxX = -std::numeric_limits<double>::infinity();
    double maxY = -std::numeric_limits<double>::infinity();

    void add(const Box& other) {
        minX = std::min(minX, other.minX);
        minY = std::min(minY, other.minY);
        maxX = std::max(maxX, other.maxX);
        maxY = std::max(maxY, other.maxY);
    }
    void add(const Point3& p) { add(Box{p.x, p.y, p.x, p.y}); }
};

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

void requirePredicateRange(const std::vector<Point2>& local, unsigned threads) {
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
            throw InvalidInputError("Triangulator: coordinate (" + std::to_string(p.x) + ", " +
                                    std::to_string(p.y) +
                                    ") is outside the supported magnitude range 1e-60 .. 1e70");
}

void requireTwoDimensions(const std::vector<Point2>& local) {
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

    const std::vector<Survivor> survivors = mergeDuplicates(points, policy);
    PreparedPoints prepared;
    prepared.duplicateCount = points.size() - survivors.size();
    prepared.sourceIndex.resize(survivors.size());
    prepared.z.resize(survivors.size());
    detail::parallelFor(survivors.size(), threads,
                        [&](unsigned, std::size_t begin, std::size_t end) {
                            for (std::size_t k = begin; k < end; ++k) {
                                prepared.sourceIndex[k] = survivors[k].source;
                                prepared.z[k] = survivors[k].z;
                            }
                        });
    prepared.origin = chooseOrigin(points, prepared.sourceIndex, threads);
    prepared.local.resize(survivors.size());
    detail::parallelFor(
        survivors.size(), threads, [&](unsigned, std::size_t begin, std::size_t end) {
            for (std::size_t k = begin; k < end; ++k) {
                const Point3& p = points[prepared.sourceIndex[k]];
                prepared.local[k] = {p.x - prepared.origin.x, p.y - prepared.origin.y};
            }
        });

    requirePredicateRange(prepared.local, threads);
    requireTwoDimensions(prepared.local);
    return prepared;
}

} // namespace terratin

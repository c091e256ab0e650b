#include "insertion_order.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <utility>

namespace terratin::detail {

namespace {

// splitmix64 (Steele, Lea & Flood 2014): tiny state, passes BigCrush, fully portable.
class SplitMix64 {
public:
    explicit SplitMix64(std::uint64_t seed) : m_state(seed) {}
    std::uint64_t operator()() {
        std::uint64_t z = (m_state += 0x9E3779B97F4A7C15ULL);
        z = (z ^ (z >> 30U)) * 0xBF58476D1CE4E5B9ULL;
        z = (z ^ (z >> 27U)) * 0x94D049BB133111EBULL;
        return z ^ (z >> 31U);
    }

private:
    std::uint64_t m_state;
};

// Uniform integer in [0, bound) without modulo bias (Lemire 2019, "Fast random integer
// generation in an interval").
std::uint32_t boundedRandom(SplitMix64& random, std::uint32_t bound) {
    auto product = (random() >> 32U) * std::uint64_t{bound};
    auto low = static_cast<std::uint32_t>(product);
    if (low < bound) {
        const std::uint32_t threshold = (0U - bound) % bound;
        while (low < threshold) {
            product = (random() >> 32U) * std::uint64_t{bound};
            low = static_cast<std::uint32_t>(product);
        }
    }
    return static_cast<std::uint32_t>(product >> 32U);
}

// Cells per axis of the grid the Hilbert curve runs through. 2^16 resolves a million points
// far below one point per cell; finer grids only lengthen the keys.
constexpr std::uint32_t kHilbertOrder = 16;
constexpr std::uint32_t kHilbertSide = 1U << kHilbertOrder;

// Position of cell (x, y) along the Hilbert curve filling a kHilbertSide square (the classic
// rotate-and-reflect construction, one quadrant per level).
std::uint32_t hilbertIndex(std::uint32_t x, std::uint32_t y) {
    std::uint32_t index = 0;
    for (std::uint32_t side = kHilbertSide / 2; side > 0; side /= 2) {
        const std::uint32_t rx = (x & side) != 0 ? 1U : 0U;
        const std::uint32_t ry = (y & side) != 0 ? 1U : 0U;
        index += side * side * ((3U * rx) ^ ry);
        if (ry == 0) {
            if (rx == 1) {
                x = kHilbertSide - 1 - x;
                y = kHilbertSide - 1 - y;
            }
            std::swap(x, y);
        }
    }
    return index;
}

// Maps a coordinate of [lo, hi] to a Hilbert grid cell.
std::uint32_t gridCell(double value, double lo, double hi) {
    if (!(hi > lo))
        return 0;
    const double cell = (value - lo) / (hi - lo) * (kHilbertSide - 1);
    return static_cast<std::uint32_t>(std::clamp(cell, 0.0, double{kHilbertSide - 1}));
}

} // namespace

std::vector<std::uint32_t> randomInsertionOrder(std::uint32_t count, std::uint32_t skip,
                                                std::uint64_t seed) {
    std::vector<std::uint32_t> order;
    order.reserve(count);
    for (std::uint32_t v = 0; v < count; ++v)
        if (v != skip)
            order.push_back(v);
    SplitMix64 random(seed);
    for (std::size_t i = order.size(); i > 1; --i) {
        const std::uint32_t j = boundedRandom(random, static_cast<std::uint32_t>(i));
        std::swap(order[i - 1], order[j]);
    }
    return order;
}

std::vector<std::uint32_t> brioInsertionOrder(std::span<const Point2> points, std::uint32_t skip,
                                              std::uint64_t seed,
                                              std::vector<std::size_t>* roundStarts) {
    double minX = std::numeric_limits<double>::infinity();
    double minY = minX;
    double maxX = -minX;
    double maxY = -minX;
    for (const Point2& p : points) {
        minX = std::min(minX, p.x);
        maxX = std::max(maxX, p.x);
        minY = std::min(minY, p.y);
        maxY = std::max(maxY, p.y);
    }
    // Sort key: the round (sparsest first) above the Hilbert index. The round of a point is
    // the number of trailing zero bits of a random word: k with probability 2^-(k+1).
    constexpr std::uint64_t kMaxRound = 63;
    SplitMix64 random(seed);
    std::vector<std::pair<std::uint64_t, std::uint32_t>> keyed;
    keyed.reserve(points.size());
    for (std::uint32_t v = 0; v < points.size(); ++v) {
        if (v == skip)
            continue;
        const auto round = static_cast<std::uint64_t>(std::countr_zero(random() | (1ULL << 62U)));
        const std::uint32_t hilbert = hilbertIndex(gridCell(points[v].x, minX, maxX),
                                                   gridCell(points[v].y, minY, maxY));
        keyed.emplace_back(((kMaxRound - round) << 32U) | hilbert, v);
    }
    std::sort(keyed.begin(), keyed.end());
    std::vector<std::uint32_t> order;
    order.reserve(keyed.size());
    for (std::size_t i = 0; i < keyed.size(); ++i) {
        order.push_back(keyed[i].second);
        if (roundStarts != nullptr && (i == 0 || (keyed[i].first >> 32U) != (keyed[i - 1].first >> 32U)))
            roundStarts->push_back(i);
    }
    return order;
}

} // namespace terratin::detail

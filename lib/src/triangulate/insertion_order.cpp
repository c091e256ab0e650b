#include "insertion_order.hpp"

#include "../parallel/parallel_for.hpp"
#include "box.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
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

// Cells per axis of the grid the Hilbert curve runs through: 2^13, 67 million cells, far more
// than the points of a round need for locality, and small enough that the round, the
// Hilbert index and the vertex id pack into one 64-bit sort key.
constexpr int kHilbertOrder = 13;
constexpr std::uint32_t kHilbertSide = 1U << kHilbertOrder;

// One level of the Hilbert curve: the quadrant (bx, by) of a cell, seen in the frame of the
// current state, gives the curve's next base-4 digit and the frame of the level below. The
// frame is a swap and/or a complement of both coordinates; those transforms commute, so the
// state is two bits: bit 0 swapped, bit 1 complemented.
struct HilbertStep {
    std::uint32_t digit;
    std::uint32_t state;
};

constexpr HilbertStep hilbertStep(std::uint32_t bx, std::uint32_t by, std::uint32_t state) {
    std::uint32_t swapped = state & 1U;
    std::uint32_t complemented = state >> 1U;
    const std::uint32_t exchange = (bx ^ by) & swapped;
    bx ^= exchange ^ complemented;
    by ^= exchange ^ complemented;
    const std::uint32_t digit = (3U * bx) ^ by;
    const std::uint32_t lowerHalf = by ^ 1U;
    swapped ^= lowerHalf;
    complemented ^= bx & lowerHalf;
    return {digit, swapped | (complemented << 1U)};
}

// Four levels at once: entry (state, x nibble, y nibble) holds the curve's next 8 bits and,
// above them, the state after those levels. Evaluating the levels one by one was the most
// expensive part of ordering a million points (a chain of dependent bit operations per level).
constexpr unsigned kNibbleLevels = 4;
using NibbleTable = std::array<std::uint16_t, 4 * 16 * 16>;

constexpr NibbleTable makeNibbleTable() {
    NibbleTable table{};
    for (std::uint32_t state = 0; state < 4; ++state)
        for (std::uint32_t x = 0; x < 16; ++x)
            for (std::uint32_t y = 0; y < 16; ++y) {
                std::uint32_t digits = 0;
                std::uint32_t next = state;
                for (int level = kNibbleLevels - 1; level >= 0; --level) {
                    const HilbertStep step =
                        hilbertStep((x >> level) & 1U, (y >> level) & 1U, next);
                    digits = (digits << 2U) | step.digit;
                    next = step.state;
                }
                table[(state << 8U) | (x << 4U) | y] =
                    static_cast<std::uint16_t>(digits | (next << 8U));
            }
    return table;
}

constexpr NibbleTable kNibbleTable = makeNibbleTable();

// Position of cell (x, y) along the Hilbert curve filling a kHilbertSide square: the levels
// above a multiple of four one at a time, then four at a time.
std::uint32_t hilbertIndex(std::uint32_t x, std::uint32_t y) {
    std::uint32_t index = 0;
    std::uint32_t state = 0;
    int level = kHilbertOrder - 1;
    for (; level >= 0 && (level + 1) % kNibbleLevels != 0; --level) {
        const HilbertStep step = hilbertStep((x >> level) & 1U, (y >> level) & 1U, state);
        index = (index << 2U) | step.digit;
        state = step.state;
    }
    for (; level >= 0; level -= kNibbleLevels) {
        const unsigned shift = static_cast<unsigned>(level) + 1 - kNibbleLevels;
        const std::uint32_t entry =
            kNibbleTable[(state << 8U) | (((x >> shift) & 15U) << 4U) | ((y >> shift) & 15U)];
        index = (index << (2 * kNibbleLevels)) | (entry & 0xFFU);
        state = entry >> 8U;
    }
    return index;
}

// Least-significant-digit radix sort of the keys on their bits [lowBit, 64): linear time, and
// each pass a sequential read and 256 sequential write streams, where a comparison sort of a
// million keys costs several times more. (11-bit digits, three passes instead of four, were
// no faster on a million keys.) Each pass runs on up to `threads` threads: every block
// counts its digits, and scatters from its own offsets, which keeps the sort stable.
void radixSort(HugePageArray<std::uint64_t>& keys, unsigned lowBit, unsigned threads) {
    constexpr unsigned kDigitBits = 8;
    constexpr std::size_t kBuckets = std::size_t{1} << kDigitBits;
    HugePageArray<std::uint64_t> buffer(keys.size());
    const unsigned blocks = parallelForThreads(keys.size(), threads);
    std::vector<std::array<std::size_t, kBuckets>> offsets(blocks);
    for (unsigned shift = lowBit; shift < 64; shift += kDigitBits) {
        const auto digit = [shift](std::uint64_t key) { return (key >> shift) & (kBuckets - 1); };
        parallelFor(keys.size(), threads, [&](unsigned block, std::size_t begin, std::size_t end) {
            offsets[block].fill(0);
            for (std::size_t i = begin; i < end; ++i)
                ++offsets[block][digit(keys[i])];
        });
        // Bucket by bucket, block by block: where each block's keys of each digit go.
        std::size_t total = 0;
        for (std::size_t bucket = 0; bucket < kBuckets; ++bucket)
            for (unsigned block = 0; block < blocks; ++block)
                total += std::exchange(offsets[block][bucket], total);
        parallelFor(keys.size(), threads, [&](unsigned block, std::size_t begin, std::size_t end) {
            std::array<std::size_t, kBuckets>& next = offsets[block];
            for (std::size_t i = begin; i < end; ++i)
                buffer[next[digit(keys[i])]++] = keys[i];
        });
        keys.swap(buffer);
    }
}

// Maps a coordinate of [lo, hi] to a Hilbert grid cell.
std::uint32_t gridCell(double value, double lo, double hi) {
    if (!(hi > lo))
        return 0;
    const double cell = (value - lo) / (hi - lo) * (kHilbertSide - 1);
    return static_cast<std::uint32_t>(std::clamp(cell, 0.0, double{kHilbertSide - 1}));
}

} // namespace

HugePageArray<std::uint32_t> randomInsertionOrder(std::uint32_t count, std::uint32_t skip,
                                                  std::uint64_t seed) {
    HugePageArray<std::uint32_t> order;
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

HugePageArray<std::uint32_t> brioInsertionOrder(std::span<const Point2> points, std::uint32_t skip,
                                                std::uint64_t seed,
                                                std::vector<std::size_t>* roundStarts,
                                                unsigned threads) {
    Box box;
    for (const Point2& p : points)
        box.add(p);
    // Sort key, from the top: the round (sparsest first), the Hilbert index, the vertex id.
    // The round of a point is the number of trailing zero bits of a random word, so k with
    // probability 2^-(k+1), capped at kMaxRound (a round of 2^-32 of the points).
    constexpr unsigned kRoundBits = 5;
    constexpr std::uint64_t kMaxRound = (1U << kRoundBits) - 1;
    constexpr unsigned kHilbertShift = 32;
    constexpr unsigned kRoundShift = kHilbertShift + 2 * kHilbertOrder;
    // The round comes from a hash of (seed, vertex) rather than one random stream, so that
    // threads can compute the keys of their blocks independently and identically.
    HugePageArray<std::uint64_t> keys(points.size() - (skip < points.size() ? 1 : 0));
    parallelFor(points.size(), threads, [&](unsigned, std::size_t begin, std::size_t end) {
        for (auto v = static_cast<std::uint32_t>(begin); v < end; ++v) {
            if (v == skip)
                continue;
            const std::uint64_t word = SplitMix64(seed ^ (std::uint64_t{v} << 32U))();
            const auto round =
                static_cast<std::uint64_t>(std::countr_zero(word | (1ULL << kMaxRound)));
            const std::uint64_t hilbert = hilbertIndex(gridCell(points[v].x, box.minX, box.maxX),
                                                       gridCell(points[v].y, box.minY, box.maxY));
            keys[v < skip ? v : v - 1] =
                ((kMaxRound - round) << kRoundShift) | (hilbert << kHilbertShift) | v;
        }
    });
    radixSort(keys, kHilbertShift, threads);
    HugePageArray<std::uint32_t> order(keys.size());
    parallelFor(keys.size(), threads, [&](unsigned, std::size_t begin, std::size_t end) {
        for (std::size_t i = begin; i < end; ++i)
            order[i] = static_cast<std::uint32_t>(keys[i]);
    });
    // At most 32 rounds: each one's end is found by binary search in the sorted keys.
    for (std::size_t i = 0; roundStarts != nullptr && i < keys.size();) {
        roundStarts->push_back(i);
        const std::uint64_t nextRound = ((keys[i] >> kRoundShift) + 1) << kRoundShift;
        i = static_cast<std::size_t>(
            std::lower_bound(keys.begin() + static_cast<std::ptrdiff_t>(i), keys.end(), nextRound) -
            keys.begin());
    }
    return order;
}

} // namespace terratin::detail

#include "distinct_points.hpp"

#include "../parallel/parallel_for.hpp"

#include <algorithm>
#include <atomic>
#include <bit>
#include <cstddef>
#include <utility>

namespace terratin::detail {

namespace {

// Bits of a coordinate with -0 folded onto +0, so that equal doubles hash equally.
std::uint64_t coordinateBits(double value) {
    return std::bit_cast<std::uint64_t>(value == 0.0 ? 0.0 : value);
}

std::uint64_t positionHash(double x, double y) {
    // A multiply-xorshift mix (the finaliser of splitmix64) of both coordinates: cheap and
    // spreads grid coordinates, whose low mantissa bits are all zero, over the whole table.
    std::uint64_t h = coordinateBits(x) * 0x9E3779B97F4A7C15ULL ^ coordinateBits(y);
    h = (h ^ (h >> 30U)) * 0xBF58476D1CE4E5B9ULL;
    h = (h ^ (h >> 27U)) * 0x94D049BB133111EBULL;
    return h ^ (h >> 31U);
}

// A point copied into its partition with its coordinates, so that finding duplicates within a
// partition reads one array front to back instead of the input at random.
struct PartitionEntry {
    double x;
    double y;
    std::uint32_t index;
};

// Points per partition, about: the partition's hash table (twice as many 32-bit slots) and
// its entries then stay in the core's caches.
constexpr std::size_t kPointsPerPartition = 4096;
constexpr unsigned kMaxPartitionBits = 12;

// Finds the duplicates within one partition with a small open-addressing table of positions
// in the partition; the entries are in ascending input index, so the first of each (x, y)
// enters the table and the later ones are reported against it.
void findDuplicatesInPartition(std::span<const PartitionEntry> entries,
                               std::vector<std::uint32_t>& table,
                               std::vector<DuplicatePoint>& duplicates) {
    constexpr std::uint32_t kEmpty = 0xFFFFFFFFU;
    const std::size_t capacity = std::bit_ceil(std::max<std::size_t>(2 * entries.size(), 16));
    table.assign(capacity, kEmpty);
    for (std::uint32_t e = 0; e < entries.size(); ++e) {
        const PartitionEntry& entry = entries[e];
        std::size_t slot = positionHash(entry.x, entry.y) & (capacity - 1);
        for (;; slot = (slot + 1) & (capacity - 1)) {
            if (table[slot] == kEmpty) {
                table[slot] = e;
                break;
            }
            const PartitionEntry& first = entries[table[slot]];
            if (first.x == entry.x && first.y == entry.y) {
                duplicates.push_back({entry.index, first.index});
                break;
            }
        }
    }
}

// The points grouped by partition, each group in ascending index, and where each group
// starts (one more entry than groups). Two streaming passes over blocks of the input on the
// threads: count per block and partition, then scatter.
struct Partitions {
    HugePageArray<PartitionEntry> entries;
    std::vector<std::size_t> start;
};

Partitions scatterIntoPartitions(std::span<const Point3> points, unsigned partitionBits,
                                 unsigned threads) {
    const std::size_t partitions = std::size_t{1} << partitionBits;
    const auto partitionOf = [partitionBits](const Point3& p) -> std::size_t {
        return partitionBits == 0 ? 0 : positionHash(p.x, p.y) >> (64U - partitionBits);
    };
    // Where each block's points of each partition go: partition by partition, then block by
    // block, which keeps every partition in ascending index.
    const unsigned blocks = parallelForThreads(points.size(), threads);
    std::vector<std::vector<std::size_t>> next(blocks, std::vector<std::size_t>(partitions, 0));
    parallelFor(points.size(), threads, [&](unsigned block, std::size_t begin, std::size_t end) {
        for (std::size_t i = begin; i < end; ++i)
            ++next[block][partitionOf(points[i])];
    });
    Partitions grouped;
    grouped.start.resize(partitions + 1);
    std::size_t total = 0;
    for (std::size_t partition = 0; partition < partitions; ++partition) {
        grouped.start[partition] = total;
        for (unsigned block = 0; block < blocks; ++block)
            total += std::exchange(next[block][partition], total);
    }
    grouped.start[partitions] = total;
    grouped.entries.resize(points.size());
    parallelFor(points.size(), threads, [&](unsigned block, std::size_t begin, std::size_t end) {
        for (std::size_t i = begin; i < end; ++i) {
            const Point3& p = points[i];
            grouped.entries[next[block][partitionOf(p)]++] = {p.x, p.y,
                                                              static_cast<std::uint32_t>(i)};
        }
    });
    return grouped;
}

// The indices in [0, count) that are not duplicates (sorted by index), in order: each block
// of the range writes its own after those of the blocks before it.
HugePageArray<std::uint32_t> indicesBesides(std::span<const DuplicatePoint> duplicates,
                                            std::size_t count, unsigned threads) {
    const auto duplicatesBefore = [&](std::size_t i) {
        return static_cast<std::size_t>(
            std::lower_bound(duplicates.begin(), duplicates.end(), i,
                             [](const DuplicatePoint& d, std::size_t v) { return d.index < v; }) -
            duplicates.begin());
    };
    HugePageArray<std::uint32_t> others(count - duplicates.size());
    parallelFor(count, threads, [&](unsigned, std::size_t begin, std::size_t end) {
        std::size_t duplicate = duplicatesBefore(begin);
        std::size_t out = begin - duplicate;
        for (std::size_t i = begin; i < end; ++i) {
            if (duplicate < duplicates.size() && duplicates[duplicate].index == i)
                ++duplicate;
            else
                others[out++] = static_cast<std::uint32_t>(i);
        }
    });
    return others;
}

} // namespace

// The points are scattered into partitions by the top bits of their position's hash, then
// each partition finds its duplicates in cache (partitions on the threads). A single table
// over all points was slower: every probe a cache miss in a table of megabytes.
DistinctPoints findDistinctPoints(std::span<const Point3> points, unsigned threads) {
    const auto partitionBits = static_cast<unsigned>(std::min<std::size_t>(
        kMaxPartitionBits, std::bit_width(points.size() / kPointsPerPartition)));
    const Partitions partitions = scatterIntoPartitions(points, partitionBits, threads);

    // Every thread takes the next partition in turn (each holds thousands of points, so one
    // atomic step per partition costs nothing).
    const std::size_t partitionCount = partitions.start.size() - 1;
    const auto workers = static_cast<unsigned>(std::clamp<std::size_t>(threads, 1, partitionCount));
    std::vector<std::vector<DuplicatePoint>> found(workers);
    std::atomic<std::size_t> nextPartition{0};
    runOnThreads(workers, [&](unsigned worker) {
        std::vector<std::uint32_t> table;
        for (std::size_t p = nextPartition++; p < partitionCount; p = nextPartition++)
            findDuplicatesInPartition(
                std::span(partitions.entries)
                    .subspan(partitions.start[p], partitions.start[p + 1] - partitions.start[p]),
                table, found[worker]);
    });
    DistinctPoints distinct;
    for (const std::vector<DuplicatePoint>& own : found)
        distinct.duplicates.insert(distinct.duplicates.end(), own.begin(), own.end());
    std::sort(distinct.duplicates.begin(), distinct.duplicates.end(),
              [](const DuplicatePoint& a, const DuplicatePoint& b) { return a.index < b.index; });
    distinct.firstOccurrences = indicesBesides(distinct.duplicates, points.size(), threads);
    return distinct;
}

} // namespace terratin::detail

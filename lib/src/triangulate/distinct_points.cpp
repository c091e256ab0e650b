#include "distinct_points.hpp"

#include "parallel_for.hpp"

#include <algorithm>
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

} // namespace

// The points are scattered into partitions by the top bits of their position's hash (two
// streaming passes, blocks of the input on the threads), then each partition finds its
// duplicates in cache (partitions on the threads). A single table over all points was
// slower: every probe a cache miss in a table of megabytes.
DistinctPoints findDistinctPoints(std::span<const Point3> points, unsigned threads) {
    const std::size_t count = points.size();
    const auto partitionBits = static_cast<unsigned>(
        std::min<std::size_t>(kMaxPartitionBits, std::bit_width(count / kPointsPerPartition)));
    const std::size_t partitions = std::size_t{1} << partitionBits;
    const auto partitionOf = [partitionBits](const Point3& p) -> std::size_t {
        return partitionBits == 0 ? 0 : positionHash(p.x, p.y) >> (64U - partitionBits);
    };

    // Where each block's points of each partition go: partition by partition, then block by
    // block, so that every partition lists its points in ascending index.
    const unsigned blocks = parallelForThreads(count, threads);
    std::vector<std::vector<std::size_t>> next(blocks, std::vector<std::size_t>(partitions, 0));
    parallelFor(count, threads, [&](unsigned block, std::size_t begin, std::size_t end) {
        for (std::size_t i = begin; i < end; ++i)
            ++next[block][partitionOf(points[i])];
    });
    std::vector<std::size_t> partitionStart(partitions + 1, 0);
    std::size_t total = 0;
    for (std::size_t partition = 0; partition < partitions; ++partition) {
        partitionStart[partition] = total;
        for (unsigned block = 0; block < blocks; ++block)
            total += std::exchange(next[block][partition], total);
    }
    partitionStart[partitions] = total;
    std::vector<PartitionEntry> entries(count);
    parallelFor(count, threads, [&](unsigned block, std::size_t begin, std::size_t end) {
        for (std::size_t i = begin; i < end; ++i) {
            const Point3& p = points[i];
            entries[next[block][partitionOf(p)]++] = {p.x, p.y, static_cast<std::uint32_t>(i)};
        }
    });

    std::vector<std::vector<DuplicatePoint>> found(blocks);
    parallelForChunks(
        partitions, threads, 16, [&](unsigned block, std::size_t begin, std::size_t end) {
            std::vector<std::uint32_t> table;
            for (std::size_t partition = begin; partition < end; ++partition)
                findDuplicatesInPartition(std::span(entries).subspan(partitionStart[partition],
                                                                     partitionStart[partition + 1] -
                                                                         partitionStart[partition]),
                                          table, found[block]);
        });
    DistinctPoints distinct;
    for (const std::vector<DuplicatePoint>& own : found)
        distinct.duplicates.insert(distinct.duplicates.end(), own.begin(), own.end());
    std::sort(distinct.duplicates.begin(), distinct.duplicates.end(),
              [](const DuplicatePoint& a, const DuplicatePoint& b) { return a.index < b.index; });

    // The first occurrences are the other points: each block copies its own after those of
    // the blocks before it.
    const auto duplicatesBefore = [&](std::size_t i) {
        return static_cast<std::size_t>(
            std::lower_bound(distinct.duplicates.begin(), distinct.duplicates.end(), i,
                             [](const DuplicatePoint& d, std::size_t v) { return d.index < v; }) -
            distinct.duplicates.begin());
    };
    distinct.firstOccurrences.resize(count - distinct.duplicates.size());
    parallelFor(count, threads, [&](unsigned, std::size_t begin, std::size_t end) {
        std::size_t duplicate = duplicatesBefore(begin);
        std::size_t out = begin - duplicate;
        for (std::size_t i = begin; i < end; ++i) {
            if (duplicate < distinct.duplicates.size() && distinct.duplicates[duplicate].index == i)
                ++duplicate;
            else
                distinct.firstOccurrences[out++] = static_cast<std::uint32_t>(i);
        }
    });
    return distinct;
}
} // namespace terratin::detail

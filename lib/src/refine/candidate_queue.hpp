#pragma once
/// @file
/// The refiner's priority queue of insertion candidates: greatest priority first, then the
/// lowest cell, exactly as a heap would order them, but cheap for millions of entries.
///
/// A binary or 4-ary heap of a million candidates misses the cache on every level of each
/// pop, and most popped candidates are stale (their triangle was split since), so the pops
/// were the refiner's largest sequential cost. Here candidates are first sorted into buckets
/// by the leading bits of their priority (as a float: exponent and 5 mantissa bits, so a
/// bucket spans 1/32 of an octave), which costs one append per push. Only the highest
/// non-empty bucket is kept as a heap; it holds thousands of entries, which stay in cache.
/// Priorities are never negative, so the float's bit pattern orders like its value. The
/// buckets cover the octaves 2^-16 to 2^24; lower priorities share the first bucket and
/// higher ones (+inf too) the last, which keeps the order (a bucket's heap sorts it out) and
/// the queue small: the refiner keeps two per strip.

#include "refine_mesh.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>
#include <vector>

namespace terratin::detail {

struct Candidate {
    double priority;
    std::uint32_t cell;
    /// The triangle whose scan found the cell, and its version then (RefineMesh).
    TriId triangle;
    std::uint32_t version;
};

/// Heap order: the greatest priority on top, then the lowest cell.
struct Lower {
    bool operator()(const Candidate& a, const Candidate& b) const {
        return a.priority != b.priority ? a.priority < b.priority : a.cell > b.cell;
    }
};

class CandidateQueue {
public:
    CandidateQueue() : m_buckets(kBuckets) {}

    [[nodiscard]] bool empty() const { return m_size == 0; }
    [[nodiscard]] std::size_t size() const { return m_size; }

    void push(const Candidate& candidate) {
        const std::uint32_t bucket = bucketOf(candidate.priority);
        ++m_size;
        if (!m_topHeap.empty() && bucket >= m_top) {
            m_topHeap.push_back(candidate);
            std::push_heap(m_topHeap.begin(), m_topHeap.end(), Lower{});
            return;
        }
        m_buckets[bucket].push_back(candidate);
        markFull(bucket);
    }

    /// The greatest candidate, or nullptr when the queue is empty. A bucket taken into the
    /// top heap first loses the candidates `isLive` rejects: most candidates are stale by
    /// the time their bucket comes up, and each would cost a pop from the heap. One that
    /// goes stale later can still come out: the caller tests what it pops. `isLive` must be
    /// monotone (a candidate it rejects stays rejected), so that dropping early changes
    /// nothing; it also has request(candidate), to ask ahead for the memory it reads.
    template <class IsLive> [[nodiscard]] const Candidate* top(const IsLive& isLive) {
        while (m_topHeap.empty() && m_size > 0) {
            takeHighestBucket();
            const std::size_t taken = m_topHeap.size();
            // Each test is a cache miss or two (the triangle's version, the cell's flags):
            // requested a few candidates ahead.
            constexpr std::size_t kAhead = 8;
            for (std::size_t i = 0; i < std::min(kAhead, taken); ++i)
                isLive.request(m_topHeap[i]);
            std::size_t kept = 0;
            for (std::size_t i = 0; i < taken; ++i) {
                if (i + kAhead < taken)
                    isLive.request(m_topHeap[i + kAhead]);
                if (isLive(m_topHeap[i]))
                    m_topHeap[kept++] = m_topHeap[i];
            }
            m_topHeap.resize(kept);
            m_size -= taken - kept;
            std::make_heap(m_topHeap.begin(), m_topHeap.end(), Lower{});
        }
        return m_topHeap.empty() ? nullptr : &m_topHeap.front();
    }

    /// Removes and returns the greatest candidate; requires !empty().
    Candidate pop() {
        settleTop();
        std::pop_heap(m_topHeap.begin(), m_topHeap.end(), Lower{});
        const Candidate candidate = m_topHeap.back();
        m_topHeap.pop_back();
        --m_size;
        return candidate;
    }

private:
    /// Buckets per octave (2^kSubBits), and the octaves with buckets of their own.
    static constexpr unsigned kSubBits = 5;
    static constexpr int kLowestOctave = -16;
    static constexpr int kHighestOctave = 24;
    static constexpr std::size_t kBuckets = static_cast<std::size_t>(kHighestOctave - kLowestOctave)
                                            << kSubBits;
    static_assert(kBuckets % 64 == 0);
    static constexpr std::size_t kWords = kBuckets / 64;
    static constexpr std::size_t kSummaryWords = (kWords + 63) / 64;

    /// Monotone: rounding to float never reverses an order, for non-negative floats (+inf
    /// included) the bit pattern grows with the value, and clamping keeps that.
    static std::uint32_t bucketOf(double priority) {
        constexpr unsigned kMantissaBits = 23;
        constexpr std::uint32_t kFirst = static_cast<std::uint32_t>(127 + kLowestOctave)
                                         << kSubBits;
        const std::uint32_t leading = std::bit_cast<std::uint32_t>(static_cast<float>(priority)) >>
                                      (kMantissaBits - kSubBits);
        if (leading < kFirst)
            return 0;
        return std::min<std::uint32_t>(leading - kFirst, kBuckets - 1);
    }

    void markFull(std::uint32_t bucket) {
        m_full[bucket / 64] |= std::uint64_t{1} << (bucket % 64);
        m_summary[bucket / 64 / 64] |= std::uint64_t{1} << (bucket / 64 % 64);
    }
    void markEmpty(std::uint32_t bucket) {
        std::uint64_t& word = m_full[bucket / 64];
        word &= ~(std::uint64_t{1} << (bucket % 64));
        if (word == 0)
            m_summary[bucket / 64 / 64] &= ~(std::uint64_t{1} << (bucket / 64 % 64));
    }
    /// The highest bucket holding candidates outside the top heap; requires one.
    [[nodiscard]] std::uint32_t highestFull() const {
        std::size_t s = m_summary.size() - 1;
        while (m_summary[s] == 0)
            --s;
        const std::size_t word =
            s * 64 + 63 - static_cast<std::size_t>(std::countl_zero(m_summary[s]));
        return static_cast<std::uint32_t>(word * 64 + 63 -
                                          static_cast<std::size_t>(std::countl_zero(m_full[word])));
    }

    /// Refills an empty top heap from the highest full bucket. Invariant: every candidate of a
    /// bucket at or above m_top is in the top heap while it is not empty (a candidate pushed
    /// above the bucket being consumed, which a split triangle can produce, joins the heap).
    void settleTop() {
        if (!m_topHeap.empty())
            return;
        takeHighestBucket();
        std::make_heap(m_topHeap.begin(), m_topHeap.end(), Lower{});
    }
    /// Moves the highest full bucket into the empty top heap (not yet a heap).
    void takeHighestBucket() {
        m_top = highestFull();
        std::swap(m_topHeap, m_buckets[m_top]);
        markEmpty(m_top);
    }

    std::vector<std::vector<Candidate>> m_buckets;
    std::array<std::uint64_t, kWords> m_full{};
    std::array<std::uint64_t, kSummaryWords> m_summary{};
    std::vector<Candidate> m_topHeap;
    std::uint32_t m_top = 0;
    std::size_t m_size = 0;
};

} // namespace terratin::detail

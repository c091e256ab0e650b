// The refiner's internal building blocks against brute force: the exact row intervals of a
// lattice triangle, Pick's shortcut for triangles holding only their corners, the floor
// division behind the intervals, and the candidate queue's order.

#include "candidate_queue.hpp"
#include "grid_scan.hpp"
#include "triangle_scan.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <set>
#include <utility>
#include <vector>

namespace terratin::detail {
namespace {

using Cell = std::pair<std::int64_t, std::int64_t>; // (row, col)

std::int64_t orient(const PixelCorner& p, const PixelCorner& q, std::int64_t col,
                    std::int64_t row) {
    return (q.col - p.col) * (row - p.row) - (q.row - p.row) * (col - p.col);
}

/// Every cell of a width x height grid inside or on the triangle, by orientation tests.
std::set<Cell> cellsByBruteForce(const PixelCorner& a, const PixelCorner& b, const PixelCorner& c,
                                 std::int64_t width, std::int64_t height) {
    std::set<Cell> cells;
    for (std::int64_t row = 0; row < height; ++row)
        for (std::int64_t col = 0; col < width; ++col) {
            const std::int64_t ab = orient(a, b, col, row);
            const std::int64_t bc = orient(b, c, col, row);
            const std::int64_t ca = orient(c, a, col, row);
            if ((ab >= 0 && bc >= 0 && ca >= 0) || (ab <= 0 && bc <= 0 && ca <= 0))
                cells.insert({row, col});
        }
    return cells;
}

/// A grid of rough integer elevations (many ties) in 0..maxHeight, with every holeEvery-th cell
/// an open hole's and every vertexEvery-th a vertex.
struct RoughGrid {
    std::vector<float> z;
    std::vector<std::uint8_t> flags;
    GridView view;
};
RoughGrid makeRoughGrid(std::int64_t width, std::int64_t height, std::mt19937& random,
                        int maxHeight, std::size_t holeEvery, std::size_t vertexEvery) {
    RoughGrid grid;
    std::uniform_int_distribution<int> elevation(0, maxHeight);
    grid.z.resize(static_cast<std::size_t>(width * height));
    grid.flags.assign(grid.z.size(), 0);
    for (std::size_t i = 0; i < grid.z.size(); ++i) {
        grid.z[i] = static_cast<float>(elevation(random));
        grid.flags[i] = i % holeEvery == 0     ? kCellOpenHole | kCellNoData
                        : i % vertexEvery == 0 ? kCellVertex
                                               : 0;
    }
    grid.view = {width, height, grid.z.data(), grid.flags.data()};
    return grid;
}

TEST(GridScan, RowsHoldExactlyTheCellsOfTheClosedTriangle) {
    std::mt19937 random(5);
    std::uniform_int_distribution<std::int64_t> coordinate(-3, 24);
    constexpr std::int64_t kWidth = 20;
    constexpr std::int64_t kHeight = 17;
    int onlyCorners = 0;
    for (int trial = 0; trial < 3000; ++trial) {
        const PixelCorner a{coordinate(random), coordinate(random), 0.0, 0};
        const PixelCorner b{coordinate(random), coordinate(random), 0.0, 1};
        const PixelCorner c{coordinate(random), coordinate(random), 0.0, 2};
        const PixelTriangle triangle(a, b, c);
        if (!triangle.hasArea())
            continue;
        std::set<Cell> visited;
        triangle.forEachRow(kWidth, kHeight, nullptr,
                            [&](std::int64_t row, std::int64_t lo, std::int64_t hi) {
                                for (std::int64_t col = lo; col <= hi; ++col)
                                    EXPECT_TRUE(visited.insert({row, col}).second);
                            });
        EXPECT_EQ(visited, cellsByBruteForce(a, b, c, kWidth, kHeight));
        // Pick's theorem: area 1/2 <=> no lattice point but the corners (on an unclipped grid).
        const std::set<Cell> all = cellsByBruteForce(a, b, c, 64, 64);
        const std::array<PixelCorner, 3> corners{a, b, c};
        const bool inGrid = std::all_of(corners.begin(), corners.end(), [](const PixelCorner& p) {
            return p.col >= 0 && p.row >= 0;
        });
        if (inGrid) {
            EXPECT_EQ(triangle.coversOnlyCorners(), all.size() == 3U);
            onlyCorners += triangle.coversOnlyCorners() ? 1 : 0;
        }
    }
    EXPECT_GT(onlyCorners, 0);
}

TEST(GridScan, StrictEdgesLeaveOutExactlyTheirCells) {
    // Every combination of strict edges, on triangles with horizontal edges, a corner between
    // the rows of the other two on either side, and rows clipped to bands.
    std::mt19937 random(11);
    std::uniform_int_distribution<std::int64_t> coordinate(-2, 21);
    constexpr std::int64_t kWidth = 19;
    constexpr std::int64_t kHeight = 18;
    for (int trial = 0; trial < 2000; ++trial) {
        const PixelTriangle triangle({coordinate(random), coordinate(random), 0.0, 0},
                                     {coordinate(random), coordinate(random), 0.0, 1},
                                     {coordinate(random), coordinate(random), 0.0, 2});
        if (!triangle.hasArea())
            continue;
        const std::int64_t sgn = orient(triangle.corner(0), triangle.corner(1),
                                        triangle.corner(2).col, triangle.corner(2).row) > 0
                                     ? 1
                                     : -1;
        for (int mask = 0; mask < 8; ++mask) {
            const bool strict[3] = {(mask & 1) != 0, (mask & 2) != 0, (mask & 4) != 0};
            const std::int64_t rowFrom = trial % 3 == 0 ? trial % 7 : 0;
            const std::int64_t rowTo = trial % 5 == 0 ? rowFrom + trial % 4 : kHeight;
            std::set<Cell> expected;
            for (std::int64_t row = rowFrom; row <= std::min(rowTo, kHeight - 1); ++row)
                for (std::int64_t col = 0; col < kWidth; ++col) {
                    bool inside = true;
                    for (int i = 0; i < 3; ++i)
                        inside &= sgn * orient(triangle.corner(i), triangle.corner((i + 1) % 3),
                                               col, row) >=
                                  (strict[i] ? 1 : 0);
                    if (inside)
                        expected.insert({row, col});
                }
            std::set<Cell> visited;
            triangle.forEachRow(
                kWidth, kHeight, strict,
                [&](std::int64_t row, std::int64_t lo, std::int64_t hi) {
                    EXPECT_LE(lo, hi);
                    for (std::int64_t col = lo; col <= hi; ++col)
                        EXPECT_TRUE(visited.insert({row, col}).second);
                },
                rowFrom, rowTo);
            ASSERT_EQ(visited, expected) << "trial " << trial << " mask " << mask;
        }
    }
}

TEST(GridScan, RowsAreExactAroundTheSizeOfTheVectorPath) {
    // Triangles up to 16 columns and 32 rows take a vectorised path (grid_scan.hpp), larger
    // ones the divisions: spans of 15 to 17 columns and 31 to 33 rows, with strict edges,
    // inside the grid and reaching past its columns.
    std::mt19937 random(17);
    constexpr std::int64_t kWidth = 40;
    constexpr std::int64_t kHeight = 50;
    int trials = 0;
    for (const std::int64_t columns : {15, 16, 17})
        for (const std::int64_t rows : {31, 32, 33})
            for (const std::int64_t left :
                 {std::int64_t{-1}, std::int64_t{3}, kWidth - columns + 1})
                for (int trial = 0; trial < 120; ++trial) {
                    std::uniform_int_distribution<std::int64_t> col(left, left + columns - 1);
                    std::uniform_int_distribution<std::int64_t> row(5, 5 + rows - 1);
                    // The first two corners span the whole box, so the box is the triangle's.
                    const PixelTriangle triangle({left, row(random), 0.0, 0},
                                                 {left + columns - 1, 5, 0.0, 1},
                                                 {col(random), 5 + rows - 1, 0.0, 2});
                    if (!triangle.hasArea())
                        continue;
                    const std::int64_t sgn =
                        orient(triangle.corner(0), triangle.corner(1), triangle.corner(2).col,
                               triangle.corner(2).row) > 0
                            ? 1
                            : -1;
                    const bool strict[3] = {trial % 2 == 0, trial % 3 == 0, trial % 5 == 0};
                    std::set<Cell> expected;
                    for (std::int64_t r = 0; r < kHeight; ++r)
                        for (std::int64_t c = 0; c < kWidth; ++c) {
                            bool inside = true;
                            for (int i = 0; i < 3; ++i)
                                inside &= sgn * orient(triangle.corner(i),
                                                       triangle.corner((i + 1) % 3), c, r) >=
                                          (strict[i] ? 1 : 0);
                            if (inside)
                                expected.insert({r, c});
                        }
                    std::set<Cell> visited;
                    triangle.forEachRow(kWidth, kHeight, strict,
                                        [&](std::int64_t r, std::int64_t lo, std::int64_t hi) {
                                            for (std::int64_t c = lo; c <= hi; ++c)
                                                EXPECT_TRUE(visited.insert({r, c}).second);
                                        });
                    ASSERT_EQ(visited, expected) << columns << " x " << rows << ", trial " << trial;
                    ++trials;
                }
    EXPECT_GT(trials, 900);
}

TEST(GridScan, BandsOfRowsMeasureLikeTheWholeTriangle) {
    // Rough elevations with ties (integers) and a few flagged cells; a triangle measured in
    // bands of rows and merged in order gives the same farthest cell as measured at once.
    constexpr std::int64_t kWidth = 90;
    constexpr std::int64_t kHeight = 70;
    std::mt19937 random(9);
    const RoughGrid grid = makeRoughGrid(kWidth, kHeight, random, 6, 37, 41);
    const GridView& view = grid.view;
    std::uniform_int_distribution<std::int64_t> coordinate(0, kWidth - 1);
    for (int trial = 0; trial < 300; ++trial) {
        const PixelCorner a{coordinate(random), coordinate(random) % kHeight, 3.0, 0};
        const PixelCorner b{coordinate(random), coordinate(random) % kHeight, 1.0, 1};
        const PixelCorner c{coordinate(random), coordinate(random) % kHeight, 5.0, 2};
        const PixelTriangle triangle(a, b, c);
        TriangleScan scan;
        if (!scan.prepare(a, b, c, view))
            continue;
        const ScanResult whole = scan.measure(view);
        for (const std::int64_t band : {1, 3, 32}) {
            ScanResult merged;
            for (std::int64_t row = triangle.rowMin(); row <= triangle.rowMax(); row += band)
                mergeLater(merged, measureRows(triangle, view, row, row + band - 1));
            EXPECT_EQ(merged.best, whole.best);
            EXPECT_EQ(merged.bestCell, whole.bestCell);
            EXPECT_EQ(merged.coversHole, whole.coversHole);
        }
    }
}

TEST(GridScan, MeasureFindsTheFarthestCellOfBruteForce) {
    // Elevations with many ties, flagged cells, and triangles up to the last cell of the
    // raster (where four cells at once would read past its end); tall ones are measured in
    // batches of rows. The farthest cell is the lowest-indexed of the largest errors.
    constexpr std::int64_t kWidth = 45;
    constexpr std::int64_t kHeight = 50;
    std::mt19937 random(21);
    const RoughGrid grid = makeRoughGrid(kWidth, kHeight, random, 3, 29, 31);
    const GridView& view = grid.view;
    const std::vector<float>& z = grid.z;
    const std::vector<std::uint8_t>& flags = grid.flags;
    std::uniform_int_distribution<std::int64_t> col(0, kWidth - 1);
    std::uniform_int_distribution<std::int64_t> row(0, kHeight - 1);
    int measured = 0;
    for (int trial = 0; trial < 600; ++trial) {
        // Every third triangle has a corner in the last cell.
        const PixelCorner a = trial % 3 == 0 ? PixelCorner{kWidth - 1, kHeight - 1, 2.0, 0}
                                             : PixelCorner{col(random), row(random), 2.0, 0};
        const PixelCorner b{col(random), row(random), trial % 2 == 0 ? 2.0 : 0.5, 1};
        const PixelCorner c{col(random), row(random), 2.0, 2};
        const PixelTriangle triangle(a, b, c);
        TriangleScan scan;
        if (!scan.prepare(a, b, c, view))
            continue;
        ScanResult expected;
        std::vector<RowSpan> spans;
        for (std::int64_t r = 0; r < kHeight; ++r)
            for (std::int64_t x = 0; x < kWidth; ++x) {
                const std::int64_t ab = orient(a, b, x, r);
                const std::int64_t bc = orient(b, c, x, r);
                const std::int64_t ca = orient(c, a, x, r);
                if (!((ab >= 0 && bc >= 0 && ca >= 0) || (ab <= 0 && bc <= 0 && ca <= 0)))
                    continue;
                if (spans.empty() || spans.back().row != r)
                    spans.push_back({r, x, x});
                spans.back().hi = x;
                const std::uint8_t flag = flags[static_cast<std::size_t>(r * kWidth + x)];
                expected.coversHole |= (flag & kCellOpenHole) != 0;
                if (flag != 0)
                    continue;
                const double error =
                    std::fabs(static_cast<double>(z[static_cast<std::size_t>(r * kWidth + x)]) -
                              (triangle.rowBase(r) + triangle.gradCol() * static_cast<double>(x)));
                if (error > expected.best) {
                    expected.best = error;
                    expected.bestCell = r * kWidth + x;
                }
            }
        const ScanResult found = scan.measure(view);
        EXPECT_EQ(found.best, expected.best) << "trial " << trial;
        EXPECT_EQ(found.bestCell, expected.bestCell) << "trial " << trial;
        EXPECT_EQ(found.coversHole, expected.coversHole) << "trial " << trial;
        ScanResult oneByOne;
        measureSpansOneByOne(view, triangle, spans.data(), spans.size(), oneByOne);
        EXPECT_EQ(oneByOne.best, expected.best);
        EXPECT_EQ(oneByOne.bestCell, expected.bestCell);
        ++measured;
    }
    EXPECT_GT(measured, 400);
}

TEST(GridScan, FloorDivisionIsExact) {
    std::mt19937_64 random(9);
    const std::int64_t bound = std::int64_t{1} << 40;
    std::uniform_int_distribution<std::int64_t> numerator(-bound, bound);
    std::uniform_int_distribution<std::int64_t> divisor(1, 1 << 20);
    for (int trial = 0; trial < 200000; ++trial) {
        const std::int64_t a = trial % 3 == 0 ? numerator(random) % 1000 : numerator(random);
        const std::int64_t b = trial % 5 == 0 ? divisor(random) % 7 + 1 : divisor(random);
        EXPECT_EQ(floorDivPositive(a, b), floorDiv(a, b)) << a << " / " << b;
        // Exact multiples, and one either side of them.
        const std::int64_t multiple = (a / b) * b;
        for (const std::int64_t n : {multiple - 1, multiple, multiple + 1})
            ASSERT_EQ(floorDivPositive(n, b), floorDiv(n, b)) << n << " / " << b;
    }
    // Past the double-exact range the integer path is taken.
    const std::int64_t huge = (std::int64_t{1} << 60) + 12345;
    EXPECT_EQ(floorDivPositive(huge, 7), floorDiv(huge, 7));
    EXPECT_EQ(floorDivPositive(-huge, 7), floorDiv(-huge, 7));
}

/// A live test for CandidateQueue::top that keeps every candidate.
struct KeepAll {
    bool operator()(const Candidate& /*candidate*/) const { return true; }
    void request(const Candidate& /*candidate*/) const {}
};

TEST(CandidateQueue, PopsInPriorityThenCellOrder) {
    std::mt19937 random(3);
    std::uniform_real_distribution<double> priority(0.0, 2000.0);
    std::vector<Candidate> reference;
    CandidateQueue queue;
    const auto pushBoth = [&](const Candidate& candidate) {
        reference.push_back(candidate);
        queue.push(candidate);
    };
    const auto popBoth = [&] {
        const auto greatest = std::max_element(reference.begin(), reference.end(), Lower{});
        const Candidate expected = *greatest;
        reference.erase(greatest);
        ASSERT_FALSE(queue.empty());
        const Candidate* top = queue.top(KeepAll{});
        ASSERT_NE(top, nullptr);
        EXPECT_EQ(top->priority, expected.priority);
        const Candidate got = queue.pop();
        EXPECT_EQ(got.priority, expected.priority);
        EXPECT_EQ(got.cell, expected.cell);
    };
    // Pushes interleaved with pops, some above the bucket being consumed, ties on priority
    // broken by the cell, zero, tiny, huge and infinite priorities.
    std::uint32_t cell = 0;
    for (int step = 0; step < 4000; ++step) {
        double value = priority(random);
        if (step % 17 == 0)
            value = 42.0;
        if (step % 101 == 0)
            value = 0.0;
        if (step % 211 == 0)
            value = std::numeric_limits<double>::infinity();
        // Below and above the octaves with buckets of their own: they share the end buckets.
        if (step % 13 == 0)
            value = 1e-9 * static_cast<double>(step % 50);
        if (step % 23 == 0)
            value = 1e9 + static_cast<double>(step % 7);
        pushBoth({value, (cell++ * 7919U) % 100003U, 0, 0});
        if (step % 3 == 2)
            popBoth();
    }
    while (!reference.empty())
        popBoth();
    EXPECT_TRUE(queue.empty());
}

TEST(CandidateQueue, TopWithALiveTestDropsDeadCandidatesAndKeepsTheOrder) {
    // Candidates die (for good) while queued. top(isLive) drops those already dead when their
    // bucket comes up; one that dies later may still come out. The live ones come out in
    // exactly the order of a queue that never held the dead.
    std::mt19937 random(4);
    std::uniform_real_distribution<double> priority(0.0, 500.0);
    std::vector<std::uint8_t> dead(3000, 0);
    struct IsLive {
        const std::vector<std::uint8_t>& dead;
        mutable int requests = 0;
        bool operator()(const Candidate& candidate) const { return dead[candidate.cell] == 0; }
        void request(const Candidate&) const { ++requests; }
    };
    const IsLive live{dead};
    CandidateQueue queue;
    std::vector<Candidate> reference; // queued and live
    for (std::uint32_t cell = 0; cell < dead.size(); ++cell) {
        const Candidate candidate{cell % 50 == 0 ? 7.0 : priority(random), cell, 0, 0};
        queue.push(candidate);
        reference.push_back(candidate);
    }
    std::size_t livePops = 0;
    std::size_t deadPops = 0;
    for (const Candidate* top = queue.top(live); top != nullptr; top = queue.top(live)) {
        const std::uint32_t topCell = top->cell; // pop() moves what top points at
        const Candidate got = queue.pop();
        EXPECT_EQ(got.cell, topCell);
        std::erase_if(reference, [&](const Candidate& c) { return dead[c.cell] != 0; });
        if (dead[got.cell] != 0) {
            ++deadPops;
        } else {
            const auto greatest = std::max_element(reference.begin(), reference.end(), Lower{});
            ASSERT_NE(greatest, reference.end());
            EXPECT_EQ(got.cell, greatest->cell);
            reference.erase(greatest);
            ++livePops;
        }
        for (int k = 0; k < 3; ++k)
            dead[random() % dead.size()] = 1;
    }
    EXPECT_TRUE(reference.empty());
    EXPECT_TRUE(queue.empty());
    const auto died = static_cast<std::size_t>(std::count(dead.begin(), dead.end(), 1));
    EXPECT_GT(livePops, 300U);
    EXPECT_LT(deadPops, died / 2); // most dead candidates were dropped unpopped
    EXPECT_GT(live.requests, 0);
}

} // namespace
} // namespace terratin::detail

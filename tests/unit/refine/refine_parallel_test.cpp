// Parallel refinement: strips refined at once give the same TIN for any thread count, and
// barely change the point count against strict greedy insertion. The levels of error they go
// down by stop at the target, or at errors negligible against the first.

#include "level_schedule.hpp"
#include "refine_test_grids.hpp"

#include "terratin/refine/refine.hpp"
#include "terratin/triangulate/mesh_validation.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace terratin {
namespace {

std::vector<std::uint32_t> sortedCells(const TinMesh& mesh) {
    std::vector<std::uint32_t> cells(mesh.sourceIndex.begin(), mesh.sourceIndex.end());
    std::sort(cells.begin(), cells.end());
    return cells;
}

TEST(RefineParallel, SameTinForOneTwoAndFourThreads) {
    HeightGrid grid = test::roughTerrain(160, 120, 17);
    for (int row = 50; row < 58; ++row)
        for (int col = 70; col < 75; ++col)
            grid.z[static_cast<std::size_t>(row) * 160U + static_cast<std::size_t>(col)] =
                std::nanf("");
    RefineOptions options;
    options.maxError = 1.0;
    options.validate = true;
    options.strips = 5; // strips, pairs of strips and the shared step all insert
    options.threads = 1;
    const RefineResult one = refine(grid, options);
    EXPECT_GT(one.pairInsertions, 0U);
    for (const unsigned threads : {2U, 4U}) {
        options.threads = threads;
        const RefineResult many = refine(grid, options);
        EXPECT_EQ(many.mesh.vertexCount(), one.mesh.vertexCount()) << threads << " threads";
        EXPECT_EQ(many.mesh.triangleCount(), one.mesh.triangleCount());
        EXPECT_EQ(sortedCells(many.mesh), sortedCells(one.mesh));
        EXPECT_EQ(many.maxError, one.maxError);
        // The squares are summed in triangle order, which follows the threads' allocation
        // order: the RMSE may differ in its last bits, never more.
        EXPECT_NEAR(many.rmse, one.rmse, 1e-12 * one.rmse);
        EXPECT_LE(many.maxError, 1.0);
    }
}

TEST(RefineParallel, StripsCostFewPointsAgainstStrictGreedy) {
    const HeightGrid grid = test::roughTerrain(192, 128, 4);
    RefineOptions options;
    options.maxError = 1.5;
    options.threads = 2;
    options.strips = 1;
    const RefineResult strict = refine(grid, options);
    EXPECT_EQ(strict.strips, 1U);
    EXPECT_EQ(strict.sharedInsertions, 0U);
    for (const std::size_t strips : {2U, 4U}) {
        options.strips = strips;
        const RefineResult parallel = refine(grid, options);
        EXPECT_EQ(parallel.strips, strips);
        EXPECT_LE(parallel.maxError, 1.5);
        const double ratio = static_cast<double>(parallel.mesh.vertexCount()) /
                             static_cast<double>(strict.mesh.vertexCount());
        EXPECT_NEAR(ratio, 1.0, 0.03)
            << parallel.mesh.vertexCount() << " vs " << strict.mesh.vertexCount();
        // Most points go in within one strip; pairs of strips and the sequential step take
        // the rest.
        EXPECT_GT(parallel.pairInsertions, 0U);
        if (strips > 2) { // two strips leave no triangle spanning more than a pair
            EXPECT_GT(parallel.sharedInsertions, 0U);
        }
        EXPECT_LT(parallel.pairInsertions + parallel.sharedInsertions,
                  parallel.mesh.vertexCount() / 3);
    }
}

TEST(RefineParallel, LimitsGiveTheSameTinForAnyThreadCount) {
    // Strips take shares of the points left per level, then one thread stops exactly.
    const HeightGrid grid = test::roughTerrain(100, 100, 23);
    RefineOptions options;
    options.maxPoints = 700;
    options.strips = 4;
    options.threads = 1;
    const RefineResult one = refine(grid, options);
    options.threads = 3;
    const RefineResult three = refine(grid, options);
    EXPECT_EQ(one.mesh.vertexCount(), 700U);
    EXPECT_EQ(one.stop, RefineStop::PointLimit);
    EXPECT_EQ(sortedCells(one.mesh), sortedCells(three.mesh));

    options.maxPoints.reset();
    options.maxTriangles = 1001;
    const RefineResult triangles = refine(grid, options);
    options.threads = 1;
    const RefineResult trianglesOne = refine(grid, options);
    EXPECT_EQ(triangles.stop, RefineStop::TriangleLimit);
    EXPECT_LE(triangles.mesh.triangleCount(), 1001U);
    EXPECT_GE(triangles.mesh.triangleCount(), 999U);
    EXPECT_EQ(sortedCells(triangles.mesh), sortedCells(trianglesOne.mesh));
}

TEST(RefineLevels, EachLevelHalvesTheHighestErrorLeft) {
    EXPECT_EQ(detail::levelBelow(80.0, 5.0, 100.0, 4), 40.0);
    EXPECT_EQ(detail::levelBelow(8.0, 5.0, 100.0, 4), 5.0); // not below the target
}

TEST(RefineLevels, HolesMakeALevelOfTheirOwn_AndOneStripGoesStraightToTheTarget) {
    EXPECT_EQ(detail::levelBelow(detail::kHolePriority, 5.0, 100.0, 4),
              std::numeric_limits<double>::max());
    EXPECT_EQ(detail::levelBelow(80.0, 5.0, 100.0, 1), 5.0);
}

TEST(RefineLevels, ErrorsNegligibleAgainstTheFirst_GoStraightToTheTarget_WhenEveryCellIsUsed) {
    // No target (-1: every cell goes in): halving stops at 1e-9 of the first error.
    const double first = 100.0;
    EXPECT_EQ(detail::levelBelow(4e-7, -1.0, first, 4), 2e-7);
    EXPECT_EQ(detail::levelBelow(1.5e-7, -1.0, first, 4), -1.0);
    // A flat grid used whole: every error is 0, one level.
    EXPECT_EQ(detail::levelBelow(0.0, -1.0, 0.0, 4), -1.0);
}

TEST(RefineLevels, PlaneUsedWhole_SkipsTheLevelsOfRoundingNoise) {
    // Slopes of 0.1 and 0.3 are not exact in binary: the plane's interpolated elevations are
    // off by rounding (~1e-14 m), and those errors would each take levels of their own down to
    // zero (23 levels here without kNegligibleErrorFraction). The bump makes the first error
    // large, so they fall below the floor.
    const HeightGrid grid = test::makeGrid(96, 64, [](int row, int col) {
        return 0.1 * col + 0.3 * row + (row == 31 && col == 47 ? 1000.0 : 0.0);
    });
    RefineOptions options;
    options.strips = 3;
    options.threads = 2;
    const RefineResult result = refine(grid, options);
    EXPECT_EQ(result.mesh.vertexCount(), grid.cellCount());
    EXPECT_LE(result.levels, 8U);
}

} // namespace
} // namespace terratin

// Greedy refinement on grids made in the test: what a plane, a spike and a ridge need, the
// max-error guarantee checked independently of the refiner, limits, and exactness.

#include "refine_test_grids.hpp"

#include "terratin/error.hpp"
#include "terratin/refine/refine.hpp"
#include "terratin/triangulate/mesh_validation.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

namespace terratin {
namespace {

using test::makeGrid;

RefineOptions withError(double maxError, unsigned threads = 1) {
    return test::validatedOptions(maxError, threads);
}

TEST(Refine, PlaneNeedsOnlyItsCorners) {
    const HeightGrid grid =
        makeGrid(40, 30, [](int row, int col) { return 2.0 * col - 3.0 * row + 100.0; });
    const RefineResult result = refine(grid, withError(0.01));
    EXPECT_EQ(result.mesh.vertexCount(), 4U);
    EXPECT_EQ(result.mesh.triangleCount(), 2U);
    EXPECT_LE(result.maxError, 1e-9);
    EXPECT_EQ(result.coveredCells, 40U * 30U);
    EXPECT_EQ(result.uncoveredCells, 0U);
    EXPECT_TRUE(result.validated);
    test::expectWithinError(result.mesh, grid, 0.01);
}

TEST(Refine, SingleSpikeAddsOnePoint_WhenItsNeighboursLieOnTheHull) {
    // On a 3 x 3 grid the spike's neighbours lie on the hull edges between flat corners.
    const HeightGrid grid =
        makeGrid(3, 3, [](int row, int col) { return row == 1 && col == 1 ? 250.0 : 12.0; });
    const RefineResult result = refine(grid, withError(0.5));
    ASSERT_EQ(result.mesh.vertexCount(), 5U);
    // The corners and the spike, in raster order.
    EXPECT_EQ(result.mesh.sourceIndex, (MeshArray<std::uint32_t>{0, 2, 4, 6, 8}));
    EXPECT_EQ(result.maxError, 0.0);
}

TEST(Refine, SingleSpikeIsKept_AndOnlyItsNeighbourhoodIsAdded) {
    // In a wide flat grid the spike is the first point inserted; the cone it makes is wrong
    // right beside it, so four points around it follow: 4 corners + 1 + 4.
    const HeightGrid grid =
        makeGrid(33, 21, [](int row, int col) { return row == 10 && col == 17 ? 250.0 : 12.0; });
    RefineOptions options = withError(0.5);
    options.strips = 1; // strict greedy order: strips may take the points in another order
    const RefineResult result = refine(grid, options);
    EXPECT_EQ(result.mesh.vertexCount(), 9U);
    const auto has = [&](std::uint32_t row, std::uint32_t col) {
        return std::binary_search(result.mesh.sourceIndex.begin(), result.mesh.sourceIndex.end(),
                                  row * 33 + col); // vertices come in raster order
    };
    EXPECT_TRUE(has(10, 17));
    EXPECT_TRUE(has(0, 0) && has(0, 32) && has(20, 0) && has(20, 32));
    EXPECT_EQ(result.maxError, 0.0);
    test::expectWithinError(result.mesh, grid, 0.5);
    // A tolerance above the spike's height needs nothing but the corners.
    EXPECT_EQ(refine(grid, withError(240.0)).mesh.vertexCount(), 4U);
}

TEST(Refine, RidgeIsKept_WhenTheTerrainIsPiecewisePlanar) {
    // A tent along column 20: two planes meeting on the ridge line. The ridge's two ends are
    // the only points besides the corners, and the ridge line is an edge of the TIN.
    const HeightGrid grid =
        makeGrid(41, 25, [](int, int col) { return 50.0 - 5.0 * std::abs(col - 20); });
    const RefineResult result = refine(grid, withError(0.01));
    EXPECT_EQ(result.mesh.vertexCount(), 6U);
    const std::vector<std::uint32_t> cells(result.mesh.sourceIndex.begin(),
                                           result.mesh.sourceIndex.end());
    EXPECT_NE(std::find(cells.begin(), cells.end(), 20U), cells.end());
    EXPECT_NE(std::find(cells.begin(), cells.end(), 24U * 41U + 20U), cells.end());
    EXPECT_LE(result.maxError, 1e-9);
}

TEST(Refine, EveryValidCellWithinMaxError_OnRoughTerrain) {
    const HeightGrid grid = test::roughTerrain(96, 80, 7);
    for (const double maxError : {0.25, 2.0, 10.0}) {
        const RefineResult result = refine(grid, withError(maxError));
        EXPECT_EQ(result.stop, RefineStop::ErrorReached);
        EXPECT_LE(result.maxError, maxError);
        EXPECT_GT(result.rmse, 0.0);
        EXPECT_LE(result.rmse, result.maxError);
        EXPECT_EQ(result.uncoveredCells, 0U);
        test::expectWithinError(result.mesh, grid, maxError);
        EXPECT_TRUE(validateDelaunay(result.mesh).ok());
    }
}

TEST(Refine, TinComesInRasterOrder) {
    // Vertices by cell, triangles by their lowest corner, neighbours renumbered with them.
    const HeightGrid grid = test::roughTerrain(96, 80, 11);
    RefineOptions options = withError(1.0);
    options.threads = 2;
    const RefineResult result = refine(grid, options);
    const TinMesh& mesh = result.mesh;
    EXPECT_TRUE(std::is_sorted(mesh.sourceIndex.begin(), mesh.sourceIndex.end()));
    EXPECT_EQ(std::adjacent_find(mesh.sourceIndex.begin(), mesh.sourceIndex.end()),
              mesh.sourceIndex.end());
    std::vector<std::uint32_t> lowest;
    for (std::size_t t = 0; t < mesh.triangleCount(); ++t)
        lowest.push_back(std::min(
            {mesh.triangles[3 * t], mesh.triangles[3 * t + 1], mesh.triangles[3 * t + 2]}));
    EXPECT_TRUE(std::is_sorted(lowest.begin(), lowest.end()));
    for (std::size_t v = 0; v < mesh.vertexCount(); ++v) {
        const std::size_t cell = mesh.sourceIndex[v];
        EXPECT_EQ(mesh.vertices[v].z, static_cast<double>(grid.z[cell]));
    }
    EXPECT_TRUE(validateDelaunay(mesh).ok()); // twins, orientation, Euler, empty circles
    test::expectWithinError(mesh, grid, 1.0);
}

TEST(Refine, FewerPoints_WhenTheToleranceGrows) {
    const HeightGrid grid = test::roughTerrain(96, 80, 3);
    std::size_t previous = grid.cellCount() + 1;
    for (const double maxError : {0.1, 1.0, 5.0, 20.0}) {
        const RefineResult result = refine(grid, withError(maxError));
        EXPECT_LT(result.mesh.vertexCount(), previous) << "E = " << maxError;
        previous = result.mesh.vertexCount();
    }
}

TEST(Refine, EveryValidCellUsed_WithoutAnyLimit) {
    const HeightGrid grid = test::roughTerrain(20, 17, 5);
    RefineOptions options;
    options.threads = 1;
    options.validate = true;
    const RefineResult result = refine(grid, options);
    EXPECT_EQ(result.mesh.vertexCount(), grid.cellCount());
    EXPECT_EQ(result.maxError, 0.0);
}

TEST(Refine, PointLimitRespected) {
    const HeightGrid grid = test::roughTerrain(64, 64, 11);
    RefineOptions options = withError(0.0);
    options.maxPoints = 150;
    const RefineResult result = refine(grid, options);
    EXPECT_EQ(result.stop, RefineStop::PointLimit);
    EXPECT_EQ(result.mesh.vertexCount(), 150U);
    EXPECT_GT(result.maxError, 0.0);
}

TEST(Refine, TriangleLimitRespected) {
    const HeightGrid grid = test::roughTerrain(64, 64, 12);
    RefineOptions options = withError(0.0);
    options.maxTriangles = 201;
    const RefineResult result = refine(grid, options);
    EXPECT_EQ(result.stop, RefineStop::TriangleLimit);
    EXPECT_LE(result.mesh.triangleCount(), 201U);
    EXPECT_GE(result.mesh.triangleCount(), 199U);
}

TEST(Refine, FirstLimitReachedStops) {
    const HeightGrid grid = test::roughTerrain(64, 64, 13);
    RefineOptions options = withError(3.0);
    options.maxPoints = 40;
    options.maxTriangles = 1000;
    const RefineResult result = refine(grid, options);
    EXPECT_EQ(result.stop, RefineStop::PointLimit);
    EXPECT_EQ(result.mesh.vertexCount(), 40U);
}

// "At most N" holds or is refused. The hull's 4 corners are the fewest points
// (2 triangles); a smaller limit is refused with that count, the hull's own is met exactly.
TEST(Refine, LimitBelowTheHullIsRefused_D13) {
    const HeightGrid grid = test::roughTerrain(30, 30, 1);
    RefineOptions options;
    options.threads = 1;
    options.maxPoints = 2;
    EXPECT_THROW(refine(grid, options), InvalidInputError); // below any TIN
    options.maxPoints = 3;
    try {
        refine(grid, options);
        ADD_FAILURE() << "a point limit of 3 accepted for a hull of 4 corners";
    } catch (const InvalidInputError& error) {
        EXPECT_NE(std::string(error.what()).find("4 corners"), std::string::npos) << error.what();
    }
    options.maxPoints = 4;
    RefineResult result = refine(grid, options);
    EXPECT_EQ(result.mesh.vertexCount(), 4U);
    EXPECT_EQ(result.stop, RefineStop::PointLimit);
    options.maxPoints.reset();
    options.maxTriangles = 1;
    EXPECT_THROW(refine(grid, options), InvalidInputError);
    options.maxTriangles = 2;
    result = refine(grid, options);
    EXPECT_EQ(result.mesh.triangleCount(), 2U);
    EXPECT_EQ(result.stop, RefineStop::TriangleLimit);
}

// Whatever the limit, the TIN has at most that many points and triangles, on one
// thread and on several, with a ragged nodata border (a hull of many corners).
TEST(Refine, LimitsHoldForEveryValue_D13) {
    HeightGrid grid = test::roughTerrain(48, 40, 5);
    for (int row = 0; row < grid.height; ++row)
        for (int col = 0; col < grid.width; ++col)
            if (col + row % 7 < 3 || (row > 30 && col > 40 - row % 5))
                grid.z[static_cast<std::size_t>(row * grid.width + col)] = std::nanf("");
    for (const unsigned threads : {1U, 3U})
        for (const std::size_t limit : {3U, 5U, 6U, 7U, 8U, 9U, 10U, 17U, 64U, 333U}) {
            RefineOptions options;
            options.threads = threads;
            options.maxPoints = limit;
            try {
                const RefineResult result = refine(grid, options);
                EXPECT_LE(result.mesh.vertexCount(), limit) << threads << " threads";
            } catch (const InvalidInputError& error) {
                EXPECT_LT(limit, 9U) << error.what(); // only below the hull's corners
            }
            options.maxPoints.reset();
            options.maxTriangles = limit;
            try {
                const RefineResult result = refine(grid, options);
                EXPECT_LE(result.mesh.triangleCount(), limit) << threads << " threads";
            } catch (const InvalidInputError& error) {
                EXPECT_LT(limit, 9U) << error.what();
            }
        }
}

// The options' ranges, checked before anything runs, in words that name no CLI flag.
TEST(RefineOptionsCheck, RefusesValuesOutOfRange_D12) {
    const auto expectRefused = [](const RefineOptions& options, const std::string& word) {
        try {
            checkRefineOptions(options);
            ADD_FAILURE() << "accepted; expected a message about " << word;
        } catch (const InvalidInputError& error) {
            EXPECT_NE(std::string(error.what()).find(word), std::string::npos) << error.what();
            EXPECT_EQ(std::string(error.what()).find("--"), std::string::npos) << error.what();
        }
    };
    RefineOptions options;
    options.maxPoints = 2;
    expectRefused(options, "point limit");
    options.maxPoints = static_cast<std::size_t>(-5); // what "-5" wrapped to
    expectRefused(options, "point limit");
    options = {};
    options.maxTriangles = 0;
    expectRefused(options, "triangle limit");
    options.maxTriangles = static_cast<std::size_t>(-1);
    expectRefused(options, "triangle limit");
    options = {};
    options.maxHole = static_cast<std::size_t>(-3);
    expectRefused(options, "hole");
    options = {};
    options.threads = kMaxThreads + 1;
    expectRefused(options, "thread");
    options = {};
    options.maxError = -1.0;
    expectRefused(options, "maximum error");
    options = {};
    options.maxPoints = 3;
    options.maxTriangles = 1;
    options.maxHole = kMaxRefineCells;
    options.threads = kMaxThreads;
    EXPECT_NO_THROW(checkRefineOptions(options));
}

TEST(Refine, ExactDelaunay_WithRotatedNonSquareAndBottomUpGeotransforms) {
    for (const std::array<double, 6>& transform :
         {std::array<double, 6>{500000.5, 30.0, 0.0, 5000000.0, 0.0, -30.0},
          std::array<double, 6>{-71.99958333, 1.0 / 1200, 0.0, 45.0, 0.0, -1.0 / 1200},
          std::array<double, 6>{1000.0, 5.0, 0.0, 2000.0, 0.0, 7.5},
          std::array<double, 6>{350000.0, 25.0, 4.0, 4200000.0, 3.0, -25.0}}) {
        HeightGrid grid = test::roughTerrain(50, 40, 21);
        grid.geoTransform = transform;
        const RefineResult result = refine(grid, withError(1.0));
        EXPECT_TRUE(result.validated);
        EXPECT_LE(result.maxError, 1.0);
        EXPECT_EQ(result.uncoveredCells, 0U);
        test::expectWithinError(result.mesh, grid, 1.0);
    }
}

TEST(Refine, Throws_WhenTheInputIsUnusable) {
    HeightGrid empty;
    EXPECT_THROW(refine(empty, {}), InvalidInputError);
    HeightGrid noData = makeGrid(5, 5, [](int, int) { return std::nan(""); });
    EXPECT_THROW(refine(noData, {}), InvalidInputError);
    HeightGrid oneRow = makeGrid(5, 5, [](int row, int) { return row == 2 ? 1.0 : std::nan(""); });
    EXPECT_THROW(refine(oneRow, {}), InvalidInputError);
    const HeightGrid fine = test::roughTerrain(5, 5, 1);
    EXPECT_THROW(refine(fine, withError(-1.0)), InvalidInputError);
}

// An infinite elevation is refused as the full-resolution path refuses it, wherever it lies
// and on a rotated grid too: one infinite cell would collapse the TIN to a few points, all
// infinite would give z = Inf.
TEST(Refine, RefusesInfiniteElevations_D7) {
    const auto expectRefused = [](const HeightGrid& grid, const std::string& where) {
        RefineOptions options;
        options.maxError = 1.0;
        try {
            refine(grid, options);
            ADD_FAILURE() << "an infinite elevation accepted";
        } catch (const InvalidInputError& error) {
            EXPECT_NE(std::string(error.what()).find("infinite elevation"), std::string::npos)
                << error.what();
            EXPECT_NE(std::string(error.what()).find(where), std::string::npos) << error.what();
        }
    };
    const double inf = std::numeric_limits<double>::infinity();
    expectRefused(makeGrid(6, 5, [&](int, int) { return inf; }), "row 0, column 0");
    expectRefused(
        makeGrid(6, 5, [&](int row, int col) { return row == 3 && col == 2 ? -inf : 7.0; }),
        "row 3, column 2");
    HeightGrid rotated =
        makeGrid(6, 5, [&](int row, int col) { return row == 4 && col == 5 ? inf : 1.0; });
    rotated.geoTransform = {1000.0, 0.8, 0.6, 2000.0, 0.6, -0.8};
    expectRefused(rotated, "row 4, column 5");
}

// A rotated geotransform is simplified without "a point outside the hull", although the
// rounded centres of the first row are not on one line. Every limit, UTM-sized
// coordinates, square and non-square cells, 30 degrees and a shear; each cell checked.
TEST(Refine, SimplifiesRotatedGrids_D6) {
    const double angle = 30.0 * std::numbers::pi / 180.0;
    const double cs = std::cos(angle);
    const double sn = std::sin(angle);
    for (const std::array<double, 6>& transform :
         {std::array<double, 6>{455900.0, 10.0 * cs, 10.0 * sn, 5104100.0, 10.0 * sn, -10.0 * cs},
          std::array<double, 6>{455900.0, 10.0 * cs, -25.0 * sn, 5104100.0, 10.0 * sn, 25.0 * cs},
          std::array<double, 6>{455900.0, 10.0, 1.0, 5104100.0, 0.0, -10.0},
          std::array<double, 6>{455900.0, 10.0, 0.0, 5104100.0, 0.5, -10.0}}) {
        HeightGrid grid = test::roughTerrain(61, 47, 8);
        grid.geoTransform = transform;
        for (int limit = 0; limit < 3; ++limit) {
            RefineOptions options = withError(1.0, 2);
            if (limit == 1)
                options.maxPoints = 300;
            if (limit == 2)
                options.maxTriangles = 300;
            const RefineResult result = refine(grid, options);
            EXPECT_TRUE(result.validated);
            EXPECT_EQ(result.uncoveredCells, 0U);
            EXPECT_EQ(result.coveredCells, grid.cellCount());
            if (limit == 0) {
                EXPECT_LE(result.maxError, 1.0);
                test::expectWithinError(result.mesh, grid, 1.0);
            }
            if (limit == 1) {
                EXPECT_LE(result.mesh.vertexCount(), 300U);
            }
            if (limit == 2) {
                EXPECT_LE(result.mesh.triangleCount(), 300U);
            }
        }
    }
}

TEST(Refine, CancelledByProgress) {
    const HeightGrid grid = test::roughTerrain(128, 128, 2);
    RefineOptions options = withError(0.0);
    EXPECT_THROW(refine(grid, options, [](double, std::string_view) { return false; }), Cancelled);
}

TEST(Refine, ProgressRisesAndLevelsStep_WhenAHoleIsLeftOpen) {
    // Regression: an open hole's candidates have kHolePriority (infinity), and when they were
    // the first priority the progress fraction stayed 0 to the end and every level after the
    // holes' went straight to the target (two levels in all).
    const HeightGrid rough = test::roughTerrain(160, 128, 4);
    const HeightGrid grid = makeGrid(160, 128, [&](int row, int col) {
        const bool inHole = row >= 40 && row < 60 && col >= 50 && col < 80;
        return inHole ? std::numeric_limits<double>::quiet_NaN()
                      : static_cast<double>(rough.z[static_cast<std::size_t>(row) * 160 + col]);
    });
    RefineOptions options = withError(0.5, 2);
    options.strips = 4;
    std::vector<double> fractions;
    const RefineResult result = refine(grid, options, [&](double fraction, std::string_view) {
        fractions.push_back(fraction);
        return true;
    });
    ASSERT_GT(result.openHoleCells, 0U);
    EXPECT_GT(result.levels, 4U);
    EXPECT_TRUE(std::any_of(fractions.begin(), fractions.end(),
                            [](double fraction) { return fraction > 0.2 && fraction < 1.0; }));
    EXPECT_TRUE(std::is_sorted(fractions.begin(), fractions.end()));
    test::expectWithinError(result.mesh, grid, 0.5);
}

TEST(Refine, CancelledPartwayWhileStripsRunOnTwoThreads) {
    // Reports come from the calling thread while the other inserts; with a point limit the
    // fraction counts points. The fifth report stops the run.
    const HeightGrid grid = test::roughTerrain(160, 128, 3);
    RefineOptions options = withError(0.0, 2);
    options.strips = 4;
    options.maxPoints = 12000;
    int reports = 0;
    const auto progress = [&](double fraction, std::string_view) {
        EXPECT_GE(fraction, 0.0);
        EXPECT_LE(fraction, 1.0);
        return ++reports < 5;
    };
    EXPECT_THROW(refine(grid, options, progress), Cancelled);
    EXPECT_EQ(reports, 5);
}

} // namespace
} // namespace terratin

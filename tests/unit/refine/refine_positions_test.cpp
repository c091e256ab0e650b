// Refinement with the TIN at other positions than the grid's cell centres (a reprojected
// DEM): the guarantee, the holes and the Delaunay property hold at the positions, checked by
// brute force; the result does not depend on the thread count.

#include "refine_test_grids.hpp"

#include "terratin/error.hpp"
#include "terratin/refine/refine.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

namespace terratin {
namespace {

// Rows bent into arcs around a centre 200 cells below the grid (and columns into rays): a
// smooth one-to-one map, far more curved than any map projection at DEM resolutions, so the
// pixel-space scans are visibly off and the exact completion has work to do.
std::vector<Point2> bentPositions(const HeightGrid& grid) {
    constexpr double kRadius = 200.0;
    std::vector<Point2> positions(grid.cellCount());
    for (std::size_t cell = 0; cell < positions.size(); ++cell) {
        const Point2 centre = grid.cellCentre(cell); // y from -0.5 down to -(height - 0.5)
        const double radius = kRadius + centre.y;
        positions[cell] = {1000.0 + radius * std::sin(centre.x / kRadius),
                           5000.0 + radius * std::cos(centre.x / kRadius)};
    }
    return positions;
}

// Rough terrain with a 6 x 5 void (an open hole) and a single nodata cell (bridged).
HeightGrid terrainWithVoid() {
    HeightGrid grid = test::roughTerrain(70, 55, 4);
    for (int row = 20; row < 25; ++row)
        for (int col = 30; col < 36; ++col)
            grid.z[static_cast<std::size_t>(row) * 70U + static_cast<std::size_t>(col)] =
                std::nanf("");
    grid.z[40U * 70U + 10U] = std::nanf("");
    return grid;
}

// The triangles as cell triples, each from its lowest cell (orientation kept), sorted: the
// TIN independent of how its triangles are numbered.
std::vector<std::array<std::uint32_t, 3>> cellTriangles(const TinMesh& mesh) {
    std::vector<std::array<std::uint32_t, 3>> triangles(mesh.triangleCount());
    for (std::size_t t = 0; t < triangles.size(); ++t) {
        std::array<std::uint32_t, 3>& cells = triangles[t];
        for (std::size_t i = 0; i < 3; ++i)
            cells[i] = mesh.sourceIndex[mesh.triangles[3 * t + i]];
        std::rotate(cells.begin(), std::min_element(cells.begin(), cells.end()), cells.end());
    }
    std::sort(triangles.begin(), triangles.end());
    return triangles;
}

RefineOptions options(double maxError, unsigned threads) {
    return test::validatedOptions(maxError, threads);
}

TEST(RefinePositions, EveryValidCellWithinMaxErrorAtItsPosition) {
    const HeightGrid grid = test::roughTerrain(80, 60, 2);
    const std::vector<Point2> positions = bentPositions(grid);
    for (const double maxError : {0.5, 4.0}) {
        const RefineResult result = refine(grid, positions, options(maxError, 2));
        EXPECT_TRUE(result.validated);
        EXPECT_GT(result.completionPasses, 0U); // the pixel-space scans alone were not enough
        EXPECT_LE(result.maxError, maxError);
        EXPECT_LT(result.mesh.vertexCount(), grid.cellCount());
        const test::CoverageCheck check =
            test::checkCoverage(result.mesh, grid, grid.cellCount(), positions);
        EXPECT_LE(check.maxError, maxError + 1e-6) << "E = " << maxError;
        EXPECT_EQ(check.uncoveredValid, 0U);
        test::expectEmptyCircumcircles(result.mesh);
    }
}

TEST(RefinePositions, VerticesLieAtTheirCellsPositions) {
    const HeightGrid grid = test::roughTerrain(50, 40, 7);
    const std::vector<Point2> positions = bentPositions(grid);
    const RefineResult result = refine(grid, positions, options(2.0, 1));
    for (std::size_t v = 0; v < result.mesh.vertexCount(); ++v) {
        const std::uint32_t cell = result.mesh.sourceIndex[v];
        EXPECT_EQ(result.mesh.vertices[v].x, positions[cell].x);
        EXPECT_EQ(result.mesh.vertices[v].y, positions[cell].y);
        EXPECT_EQ(result.mesh.vertices[v].z, static_cast<double>(grid.z[cell]));
    }
}

TEST(RefinePositions, HolesStayOpenAtThePositionsOfTheirCells) {
    const HeightGrid grid = terrainWithVoid();
    const std::vector<Point2> positions = bentPositions(grid);
    for (const double maxError : {0.5, 6.0}) {
        const RefineResult result = refine(grid, positions, options(maxError, 2));
        EXPECT_EQ(result.openHoleCells, 30U);
        EXPECT_GT(result.droppedTriangles, 0U);
        const test::CoverageCheck check = test::checkCoverage(result.mesh, grid, 1, positions);
        EXPECT_EQ(check.coveredOpenHoleCells, 0U) << "E = " << maxError;
        EXPECT_EQ(check.uncoveredValid, result.uncoveredCells);
        EXPECT_LE(check.maxError, maxError + 1e-6);
        test::expectEmptyCircumcircles(result.mesh);
    }
}

TEST(RefinePositions, SameTinForOneTwoAndThreeThreads) {
    const HeightGrid grid = terrainWithVoid();
    const std::vector<Point2> positions = bentPositions(grid);
    const RefineResult one = refine(grid, positions, options(1.0, 1));
    for (const unsigned threads : {2U, 3U}) {
        const RefineResult other = refine(grid, positions, options(1.0, threads));
        EXPECT_EQ(other.mesh.sourceIndex, one.mesh.sourceIndex) << threads << " threads";
        EXPECT_EQ(cellTriangles(other.mesh), cellTriangles(one.mesh)) << threads << " threads";
        EXPECT_EQ(other.completionPasses, one.completionPasses);
    }
}

TEST(RefinePositions, PointLimitRespected) {
    const HeightGrid grid = test::roughTerrain(60, 60, 3);
    const std::vector<Point2> positions = bentPositions(grid);
    RefineOptions limited = options(0.0, 2);
    limited.maxPoints = 300;
    const RefineResult result = refine(grid, positions, limited);
    EXPECT_EQ(result.stop, RefineStop::PointLimit);
    EXPECT_LE(result.mesh.vertexCount(), 300U);
}

TEST(RefinePositions, BadPositionsAreRefused) {
    const HeightGrid grid = test::roughTerrain(20, 10, 1);
    std::vector<Point2> positions = bentPositions(grid);
    EXPECT_THROW(refine(grid, std::span<const Point2>(), options(1.0, 1)), InvalidInputError);
    EXPECT_THROW(refine(grid, std::span<const Point2>(positions).first(199), options(1.0, 1)),
                 InvalidInputError);
    positions[5].y = std::numeric_limits<double>::quiet_NaN();
    EXPECT_THROW(refine(grid, positions, options(1.0, 1)), InvalidInputError);
}

} // namespace
} // namespace terratin

// Nodata in refinement: holes larger than maxHole stay open (no triangle covers one of their
// cell centres), smaller ones are bridged, --fill-holes bridges all; valid cells stay covered.

#include "refine_test_grids.hpp"

#include "terratin/refine/refine.hpp"
#include "terratin/triangulate/mesh_validation.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace terratin {
namespace {

// Rough terrain with a 4 x 3 void, a diagonal pair of nodata cells (one 8-connected hole of
// two), a single nodata cell, and a nodata frame cut into two corners.
HeightGrid terrainWithHoles() {
    HeightGrid grid = test::roughTerrain(60, 50, 9);
    const auto setNoData = [&grid](int row, int col) {
        grid.z[static_cast<std::size_t>(row) * 60U + static_cast<std::size_t>(col)] = std::nanf("");
    };
    for (int row = 20; row < 23; ++row)
        for (int col = 30; col < 34; ++col)
            setNoData(row, col);
    setNoData(10, 10);
    setNoData(11, 11);
    setNoData(40, 45);
    for (int row = 0; row < 8; ++row)
        for (int col = 0; col < 8 - row; ++col) {
            setNoData(row, col);
            setNoData(49 - row, 59 - col);
        }
    return grid;
}

RefineOptions options(double maxError) {
    RefineOptions result;
    result.maxError = maxError;
    result.threads = 1;
    result.validate = true;
    return result;
}

TEST(RefineHoles, HolesStayOpenExactlyWhereTheNodataIs) {
    const HeightGrid grid = terrainWithHoles();
    for (const double maxError : {0.5, 5.0}) {
        const RefineResult result = refine(grid, options(maxError));
        EXPECT_GT(result.droppedTriangles, 0U);
        EXPECT_EQ(result.openHoleCells, 12U + 2U + 2U * 36U);
        const test::CoverageCheck check = test::checkCoverage(result.mesh, grid, 1);
        EXPECT_EQ(check.coveredOpenHoleCells, 0U);
        EXPECT_EQ(check.uncoveredValid, 0U);
        EXPECT_EQ(result.uncoveredCells, 0U);
        EXPECT_LE(check.maxError, maxError + 1e-6);
        EXPECT_LE(result.maxError, maxError);
        test::expectEmptyCircumcircles(result.mesh);
        // The single nodata cell (40, 45) is bridged: it is the one nodata cell covered.
        EXPECT_EQ(test::checkCoverage(result.mesh, grid, 0).coveredOpenHoleCells, 1U);
    }
}

TEST(RefineHoles, MaxHoleBridgesSmallerHoles) {
    const HeightGrid grid = terrainWithHoles();
    RefineOptions bridged = options(2.0);
    bridged.maxHole = 12; // the 4 x 3 void and the diagonal pair are bridged, the corners not
    const RefineResult result = refine(grid, bridged);
    EXPECT_EQ(result.openHoleCells, 2U * 36U);
    const test::CoverageCheck check = test::checkCoverage(result.mesh, grid, 12);
    EXPECT_EQ(check.coveredOpenHoleCells, 0U);
    EXPECT_EQ(check.uncoveredValid, 0U);
}

TEST(RefineHoles, FillHolesCoversEverything_AndStaysExactlyDelaunay) {
    const HeightGrid grid = terrainWithHoles();
    RefineOptions filled = options(2.0);
    filled.fillHoles = true;
    const RefineResult result = refine(grid, filled);
    EXPECT_EQ(result.droppedTriangles, 0U);
    EXPECT_EQ(result.openHoleCells, 0U);
    EXPECT_TRUE(validateDelaunay(result.mesh).ok());
    const test::CoverageCheck check = test::checkCoverage(result.mesh, grid, 0);
    EXPECT_EQ(check.uncoveredValid, 0U);
    EXPECT_LE(check.maxError, 2.0 + 1e-6);
}

TEST(RefineHoles, NoVertexIsANodataCell) {
    const HeightGrid grid = terrainWithHoles();
    const RefineResult result = refine(grid, options(1.0));
    for (const std::uint32_t cell : result.mesh.sourceIndex)
        EXPECT_FALSE(std::isnan(grid.z[cell]));
}

TEST(RefineHoles, SpareVerticesLeaveRoom_InTheTinKeptWithItsHoleTriangles) {
    const HeightGrid grid = terrainWithHoles();
    RefineOptions kept = options(0.5);
    kept.keepHoleTriangles = true;
    const RefineResult plain = refine(grid, kept);
    kept.spareVertices = 300;
    const RefineResult roomy = refine(grid, kept);
    EXPECT_EQ(roomy.mesh.vertices, plain.mesh.vertices); // the room changes nothing else
    EXPECT_EQ(roomy.mesh.triangles, plain.mesh.triangles);
    EXPECT_GT(roomy.droppedTriangles, 0U); // measured without them, returned with them
    EXPECT_GE(roomy.mesh.vertices.capacity(), roomy.mesh.vertexCount() + 300);
    EXPECT_GE(roomy.mesh.sourceIndex.capacity(), roomy.mesh.vertexCount() + 300);
    EXPECT_GE(roomy.mesh.triangles.capacity(), 3 * (roomy.mesh.triangleCount() + 2 * 300));
    EXPECT_GE(roomy.mesh.neighbours.capacity(), 3 * (roomy.mesh.triangleCount() + 2 * 300));
}

TEST(RefineHoles, WithoutTheLastMeasure_TheSameTin_AndNoFigures) {
    const HeightGrid grid = terrainWithHoles();
    for (const bool keepHoleTriangles : {true, false}) {
        RefineOptions measured = options(0.5);
        measured.keepHoleTriangles = keepHoleTriangles;
        RefineOptions unmeasured = measured;
        unmeasured.measure = false;
        const RefineResult a = refine(grid, measured);
        const RefineResult b = refine(grid, unmeasured);
        EXPECT_EQ(b.mesh.vertices, a.mesh.vertices);
        EXPECT_EQ(b.mesh.triangles, a.mesh.triangles);
        EXPECT_EQ(b.mesh.neighbours, a.mesh.neighbours);
        EXPECT_GT(a.coveredCells, 0U);
        EXPECT_EQ(b.coveredCells, 0U);
        EXPECT_EQ(b.maxError, 0.0);
        // Without their triangles over holes, both dropped the same ones.
        EXPECT_EQ(b.droppedTriangles, keepHoleTriangles ? 0U : a.droppedTriangles);
    }
}

} // namespace
} // namespace terratin

namespace terratin {
namespace {

TEST(RefineHoles, AValidCellHangingIntoAnOpenHole_IsCovered) {
    // A refined TIN covers a valid cell next to a large open hole, where dropping the
    // triangles over the hole could leave it uncovered. The full-resolution TIN covers every
    // peninsula (each is the corner of a half-cell triangle with two cells above it); the
    // simplified TIN must too.
    std::size_t peninsulas = 0;
    for (std::uint32_t seed = 1; seed <= 6; ++seed)
        for (const double maxError : {0.5, 2.0, 8.0}) {
            SCOPED_TRACE("seed " + std::to_string(seed) + ", max error " +
                         std::to_string(maxError));
            const HeightGrid grid = test::shoreWithPeninsulas(seed);
            const RefineResult result = refine(grid, options(maxError));
            const test::CoverageCheck check = test::checkCoverage(result.mesh, grid, 1);
            EXPECT_EQ(check.uncoveredValid, 0U);
            EXPECT_EQ(result.uncoveredCells, 0U);
            EXPECT_EQ(check.coveredOpenHoleCells, 0U);
            EXPECT_LE(check.maxError, maxError + 1e-6);
            test::expectEmptyCircumcircles(result.mesh);
            peninsulas += result.completionPasses;
        }
    EXPECT_GT(peninsulas, 0U) << "no grid stranded a vertex: the test tests nothing";
}

} // namespace
} // namespace terratin

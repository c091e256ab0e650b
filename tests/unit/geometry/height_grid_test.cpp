// bilinearElevation: a bilinear function of the cell numbers is reproduced anywhere among four
// valid cells, on north-up and rotated grids; a point outside the quadrilateral of the four
// centres (by one ulp), outside the grid or next to a cell without data gets NaN.

#include "terratin/geometry/height_grid.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace terratin {
namespace {

/// A bilinear function of the (fractional) column and row, exact in float32 at every cell.
double saddle(double col, double row) {
    return 100.0 + col + 2.0 * row + col * row / 4.0;
}

HeightGrid saddleGrid(const std::array<double, 6>& geoTransform) {
    HeightGrid grid;
    grid.width = 7;
    grid.height = 5;
    grid.geoTransform = geoTransform;
    grid.z.resize(grid.cellCount());
    for (int row = 0; row < grid.height; ++row)
        for (int col = 0; col < grid.width; ++col)
            grid.z[static_cast<std::size_t>(row * grid.width + col)] =
                static_cast<float>(saddle(col, row));
    return grid;
}

/// The map position of fractional cell (col, row): the centre of cell (row, col) at whole
/// numbers.
Point2 at(const HeightGrid& grid, double col, double row) {
    const std::array<double, 6>& c = grid.geoTransform;
    return {c[0] + (col + 0.5) * c[1] + (row + 0.5) * c[2],
            c[3] + (col + 0.5) * c[4] + (row + 0.5) * c[5]};
}

const std::array<double, 6> kNorthUp{500000.0, 10.0, 0.0, 4000000.0, 0.0, -10.0};
const std::array<double, 6> kRotated{500000.0, 8.0, 6.0, 4000000.0, 6.0, -8.0};

TEST(BilinearElevation, ReproducesABilinearSurfaceAmongFourCells_NorthUpAndRotated) {
    for (const std::array<double, 6>& transform : {kNorthUp, kRotated}) {
        const HeightGrid grid = saddleGrid(transform);
        for (const auto& [col, row] :
             {std::pair{0.3, 0.6}, std::pair{2.5, 1.25}, std::pair{5.9, 3.1}, std::pair{4.0, 2.0}})
            EXPECT_NEAR(bilinearElevation(grid, at(grid, col, row)), saddle(col, row), 1e-9)
                << col << ", " << row;
        // The outer cells' centres and the edges between them belong to the grid too.
        EXPECT_NEAR(bilinearElevation(grid, grid.cellCentre(4, 6)), saddle(6.0, 4.0), 1e-9);
        EXPECT_NEAR(bilinearElevation(grid, grid.cellCentre(0, 0)), saddle(0.0, 0.0), 1e-9);
        EXPECT_NEAR(bilinearElevation(grid, at(grid, 6.0, 2.5)), saddle(6.0, 2.5), 1e-9);
    }
}

TEST(BilinearElevation, NothingOutsideTheCentres_NorNextToACellWithoutData) {
    HeightGrid grid = saddleGrid(kNorthUp);
    const Point2 lastColumn = grid.cellCentre(2, 6);
    EXPECT_TRUE(std::isnan(bilinearElevation(
        grid, {std::nextafter(lastColumn.x, 1e300), lastColumn.y}))); // one ulp outside
    EXPECT_TRUE(std::isnan(bilinearElevation(grid, at(grid, -0.01, 2.0))));
    EXPECT_TRUE(std::isnan(bilinearElevation(grid, at(grid, 3.0, 4.2))));
    grid.z[2 * 7 + 3] = std::numeric_limits<float>::quiet_NaN(); // cell (2, 3)
    EXPECT_TRUE(std::isnan(bilinearElevation(grid, at(grid, 2.5, 1.5))));
    EXPECT_TRUE(std::isnan(bilinearElevation(grid, at(grid, 3.5, 2.5))));
    EXPECT_NEAR(bilinearElevation(grid, at(grid, 4.5, 2.5)), saddle(4.5, 2.5), 1e-9);
}

TEST(BilinearElevation, ASingleRowOrColumnHasNoQuadrilateral) {
    HeightGrid grid;
    grid.width = 5;
    grid.height = 1;
    grid.geoTransform = kNorthUp;
    grid.z.assign(grid.cellCount(), 1.0F);
    EXPECT_TRUE(std::isnan(bilinearElevation(grid, grid.cellCentre(0, 2))));
}

} // namespace
} // namespace terratin

// How a grid is cut into tiles: every cell in a tile, neighbouring tiles sharing exactly one
// line of cells, no tile wider than the tile size allows.

#include "tile_grid.hpp"

#include <gtest/gtest.h>

#include <stdexcept>

namespace terratin::detail {
namespace {

void expectSharedBordersAlong(std::size_t cells, std::size_t tileSize, std::size_t tiles,
                              CellRange (TileGrid::*rangeOf)(std::size_t) const,
                              const TileGrid& grid) {
    ASSERT_GE(tiles, 1U);
    EXPECT_EQ((grid.*rangeOf)(0).first, 0U);
    EXPECT_EQ((grid.*rangeOf)(tiles - 1).last, cells - 1);
    for (std::size_t k = 0; k < tiles; ++k) {
        const CellRange range = (grid.*rangeOf)(k);
        EXPECT_LE(range.count(), tileSize + 1) << cells << " " << tileSize << " " << k;
        if (cells > 1) {
            EXPECT_GE(range.count(), 2U) << "a tile of one line of cells has no area";
        }
        if (k + 1 < tiles) {
            EXPECT_EQ(range.last, (grid.*rangeOf)(k + 1).first) << "one shared line of cells";
        }
    }
}

TEST(TileGrid, CoversEveryCell_NeighboursShareOneLineOfCells) {
    for (const std::size_t cells : {1U, 2U, 3U, 7U, 8U, 9U, 10U, 17U, 100U, 257U}) {
        for (const std::size_t tileSize : {1U, 2U, 3U, 8U, 16U, 256U, 1000U}) {
            const TileGrid grid(cells, cells + 3, tileSize);
            expectSharedBordersAlong(cells, tileSize, grid.tileColumns(), &TileGrid::columnsOf,
                                     grid);
            expectSharedBordersAlong(cells + 3, tileSize, grid.tileRows(), &TileGrid::rowsOf, grid);
            EXPECT_EQ(grid.tileCount(), grid.tileColumns() * grid.tileRows());
        }
    }
}

TEST(TileGrid, TheLastTileHoldsWhatIsLeft_AsLittleAsOneCellBeyondItsBorder) {
    const TileGrid grid(10, 1, 4); // centres 0..9: intervals 0-4, 4-8, 8-9
    ASSERT_EQ(grid.tileColumns(), 3U);
    EXPECT_EQ(grid.columnsOf(0), (CellRange{0, 4}));
    EXPECT_EQ(grid.columnsOf(1), (CellRange{4, 8}));
    EXPECT_EQ(grid.columnsOf(2), (CellRange{8, 9}));
    EXPECT_EQ(grid.tileRows(), 1U);
    EXPECT_EQ(grid.rowsOf(0), (CellRange{0, 0}));
}

TEST(TileGrid, RefusesZeroSizes_AndTilesThatDoNotExist) {
    EXPECT_THROW(TileGrid(0, 5, 4), std::invalid_argument);
    EXPECT_THROW(TileGrid(5, 0, 4), std::invalid_argument);
    EXPECT_THROW(TileGrid(5, 5, 0), std::invalid_argument);
    const TileGrid grid(9, 9, 4);
    EXPECT_THROW((void)grid.columnsOf(2), std::out_of_range);
    EXPECT_THROW((void)grid.rowsOf(2), std::out_of_range);
}

} // namespace
} // namespace terratin::detail

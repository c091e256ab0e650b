#include "terratin/tile/refine_tiles.hpp"

#include "tile_refine.hpp"

#include "terratin/error.hpp"

#include <cstdint>
#include <string>

namespace terratin {

void checkTileOptions(const RefineOptions& refine, const TileOptions& tiles) {
    if (tiles.distribution != nullptr && tiles.tileSize == 0)
        throw InvalidInputError("Refiner: processes share tiles: give a tile size");
    if (tiles.everyCell && tiles.tileSize == 0)
        throw InvalidInputError("Refiner: every cell a vertex is full resolution in tiles: give "
                                "a tile size (without tiles, triangulate the cells)");
    if (tiles.tileSize == 0)
        throw InvalidInputError("Refiner: refineTiles needs a tile size");
    if (tiles.tileSize < 2 || tiles.tileSize > kMaxTileSize)
        throw InvalidInputError("Refiner: the tile size must be 2 to " +
                                std::to_string(kMaxTileSize) + " cells (got " +
                                std::to_string(tiles.tileSize) + ")");
    if (tiles.everyCell && (refine.maxError || refine.maxPoints || refine.maxTriangles))
        throw InvalidInputError("Refiner: tiles with every cell a vertex take no maximum error "
                                "and no point or triangle limit");
    if (!refine.maxError && !tiles.everyCell)
        throw InvalidInputError("Refiner: tiles need a maximum error, which decides the "
                                "vertices of their borders (with a point or triangle limit "
                                "too), or every cell a vertex");
    if (refine.spareVertices > 0)
        throw InvalidInputError("Refiner: tiles leave no room for more vertices");
}

RefineResult refineTiles(CellSource& cells, const RefineOptions& refine, const TileOptions& tiles,
                         const ProgressCallback& progress) {
    checkRefineOptions(refine);
    checkTileOptions(refine, tiles);
    if (cells.width() <= 0 || cells.height() <= 0)
        throw InvalidInputError("Refiner: the grid is empty");
    if (static_cast<std::uint64_t>(cells.width()) * static_cast<std::uint64_t>(cells.height()) >
        std::uint64_t{0xFFFFFFFFU})
        throw InvalidInputError("Refiner: tiles number the cells of at most 2^32 - 1 cells; "
                                "split the raster");
    return detail::refineInTiles(cells, detail::TiledRefineOptions(refine, tiles), progress);
}

RefineResult refineTiles(const HeightGrid& grid, const RefineOptions& refine,
                         const TileOptions& tiles, const ProgressCallback& progress) {
    checkRefineOptions(refine);
    checkTileOptions(refine, tiles);
    checkRefineGrid(grid);
    GridCells cells(grid);
    return refineTiles(cells, refine, tiles, progress);
}

} // namespace terratin

#pragma once
/// @file
/// Refinement in tiles: a DEM simplified (or kept at full resolution) tile by tile, reading a
/// tile's window of cells at a time, so that a raster larger than memory is never held whole.
/// The tiles share their border cells and the vertices chosen on them, so their TINs join
/// without cracks (docs/algorithms.md, "Tiles"). RefineOptions say how much to simplify;
/// TileOptions how the grid is cut, by whom, and where the tiles go.

#include "terratin/geometry/height_grid.hpp"
#include "terratin/geometry/point.hpp"
#include "terratin/progress.hpp"
#include "terratin/refine/refine.hpp"
#include "terratin/tile/cell_source.hpp"
#include "terratin/triangulate/tin_mesh.hpp"

#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

namespace terratin {

class TileDistribution; // tile_distribution.hpp

/// Largest TileOptions::tileSize: a tile's side fits the grid's int dimensions.
inline constexpr std::size_t kMaxTileSize = (std::size_t{1} << 31U) - 2;

/// How a tiled refinement cuts the grid and where its tiles go.
struct TileOptions {
    /// Tiles of this many cell intervals along each axis, 2 to kMaxTileSize, that share their
    /// border cells. The tiles' TINs join without cracks: each border's vertices are chosen
    /// from its cells alone, within RefineOptions::maxError, and each tile's TIN is exactly
    /// Delaunay, the whole only within tiles; a rotated grid's tiles are Delaunay in its pixel
    /// frame and then put at the cells' centres. Needs maxError (or everyCell) and takes no
    /// RefineOptions::spareVertices. A point or triangle limit is shared among the tiles in
    /// proportion to the valid cells each owns (counted in a first pass over the cells), so
    /// the whole keeps to it; a tile whose share is below what its hull and sides keep within
    /// maxError fails the run.
    std::size_t tileSize = 0;
    /// Full resolution, every valid cell a vertex. Each tile's cells are triangulated at once
    /// (exactly Delaunay, triangulate()) instead of refined, its open holes cut as a refined
    /// tile's; a side's cells are all vertices in both tiles, so the tiles join without cracks.
    /// Takes no maxError, point or triangle limit.
    bool everyCell = false;
    /// The processes that share the tiles (terratin's MPI ranks; the caller's, alive for the
    /// call); nullptr: this process refines every tile. The TIN is the same either way. In a
    /// process that does not coordinate, refineTiles refines what it is handed and returns no
    /// TIN.
    TileDistribution* distribution = nullptr;
    /// With a distribution: the bytes the coordinator may hold in tiles that came back before
    /// their turn before it hands out no more (TileDistribution::gather; 0: no bound).
    std::uint64_t earlyTileBytes = 0;
    /// Where the cells of a window of the grid lie in the TIN's CRS, row-major over the window
    /// (given as a grid with its shape, firstRow, firstColumn and geoTransform, and no
    /// elevations), as refine()'s positions: a geographic DEM's cell centres projected to its
    /// UTM zone. Windows overlap; a cell must get exactly the same position every time. Each
    /// tile is then refined at its cells' positions and its TIN cut along a boundary through
    /// its sides' vertices (docs/algorithms.md, "Tiles at projected positions"). Empty: the
    /// cells lie at their centres.
    std::function<std::vector<Point2>(const HeightGrid& window)> cellPositions;
    /// When set, receives each tile's TIN in tile order (a tile number, row-major among the
    /// tiles, and its TIN with sourceIndex = the grid's cell index; tiles without a triangle
    /// are skipped) instead of having them joined; the result then holds no TIN, only the
    /// figures. A tile's TIN shares its side vertices with its neighbours' (equal positions).
    std::function<void(std::size_t tile, TinMesh tin)> tileSink;
};

/// Throws InvalidInputError when `tiles` are outside their range or contradict `refine`: a
/// tile size of 1 or above kMaxTileSize, everyCell with a maximum error or a limit, or
/// without tiles, tiles without a maximum error (or everyCell), spare vertices with tiles, a
/// distribution without tiles. refineTiles calls it first, with checkRefineOptions.
void checkTileOptions(const RefineOptions& refine, const TileOptions& tiles);

/// refine() in tiles (tiles.tileSize > 0) over cells read a window at a time: the whole grid
/// is never held, only one tile's cells with a margin of refine.maxHole cells around them
/// (none with fillHoles), which decides the tile's holes as the whole grid would, and the
/// joined TIN. The same TIN as refine() of the whole grid with the same refine options. Same
/// exceptions as refine(), those of checkTileOptions and of `cells`; InvalidInputError when
/// the grid has 2^32 cells or more (the TIN's sourceIndex numbers them in 32 bits). Memory:
/// the TIN, and per tile its cells with their margin (5 bytes a cell) and its refinement.
RefineResult refineTiles(CellSource& cells, const RefineOptions& refine, const TileOptions& tiles,
                         const ProgressCallback& progress = {});

/// refineTiles over a grid held in memory.
RefineResult refineTiles(const HeightGrid& grid, const RefineOptions& refine,
                         const TileOptions& tiles, const ProgressCallback& progress = {});

} // namespace terratin

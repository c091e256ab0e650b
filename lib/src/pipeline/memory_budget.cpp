#include "memory_budget.hpp"

#include "terratin/error.hpp"
#include "terratin/tile/refine_tiles.hpp"

#include <gdal.h>

#include <algorithm>
#include <cmath>
#include <string>

namespace terratin::detail {

namespace {

constexpr std::uint64_t kMiB = std::uint64_t{1} << 20;
/// The process before any tile: code, GDAL's drivers, PROJ's database, the report.
constexpr std::uint64_t kProcessBytes = 96 * kMiB;
/// A tile's peak bytes per cell when every cell becomes a vertex (the refiner's grid, its
/// triangles and candidates, the tile's TIN on its way to the writer); measured on random
/// heights, where --max-error keeps them all.
constexpr std::uint64_t kTileBytesPerCell = 320;
/// What a tile at projected positions adds per cell: the positions, the constrained TIN's
/// check of every cell (tile/projected_tile.hpp).
constexpr std::uint64_t kMovedCellBytes = 128;

std::uint64_t tileBytes(std::size_t tileSize, std::size_t marginCells, std::uint64_t perCell) {
    const auto side = static_cast<std::uint64_t>(tileSize + 1 + 2 * marginCells);
    return side * side * perCell;
}

/// A limit to give, rounded up to whole MiB.
std::string mebibytes(std::uint64_t bytes) {
    return std::to_string((bytes + kMiB - 1) / kMiB) + "M";
}

/// The limit given, as given where it is whole MiB, else in bytes (not rounded up to the
/// limit it is not).
std::string givenLimit(std::uint64_t bytes) {
    return bytes % kMiB == 0 ? mebibytes(bytes) : std::to_string(bytes) + " bytes";
}

/// The limit whose share for tiles holds `bytes`: the inverse of the shares below.
std::uint64_t limitFor(std::uint64_t bytes) {
    return (kProcessBytes + bytes) * 16 / 11;
}

} // namespace

MemoryBudget memoryBudget(std::uint64_t limitBytes, std::size_t marginCells, std::size_t tileSize,
                          bool cellsMove) {
    const std::uint64_t perCell = kTileBytesPerCell + (cellsMove ? kMovedCellBytes : 0);
    const auto tileBytes = [&](std::size_t size, std::size_t margin) {
        return detail::tileBytes(size, margin, perCell);
    };
    MemoryBudget budget;
    // Of the limit: 1/16 for GDAL's cache, 1/4 for the writer, the rest for the process and
    // the tile.
    budget.gdalCacheBytes = limitBytes / 16;
    budget.writerBytes = limitBytes / 4;
    const std::uint64_t shared = budget.gdalCacheBytes + budget.writerBytes + kProcessBytes;
    const std::uint64_t forTiles = limitBytes > shared ? limitBytes - shared : 0;
    budget.tileBytes = forTiles;
    const std::string limitName = markOption("memory_limit");
    if (tileSize > 0) {
        if (tileBytes(tileSize, marginCells) > forTiles)
            throw InvalidInputError("Build: tiles of " + std::to_string(tileSize) + " cells need " +
                                    limitName + " " +
                                    mebibytes(limitFor(tileBytes(tileSize, marginCells))) +
                                    " or more; give a larger limit, or leave out " +
                                    markOption("tile_size") + " to have the tiles fit");
        budget.tileSize = tileSize;
        return budget;
    }
    const auto side = static_cast<std::size_t>(
        std::sqrt(static_cast<double>(forTiles) / static_cast<double>(perCell)));
    const std::size_t grown = 1 + 2 * marginCells;
    budget.tileSize = std::min(side > grown ? side - grown : 0, kMaxTileSize);
    if (budget.tileSize < kLeastTileSize)
        throw InvalidInputError(
            "Build: " + limitName + " " + givenLimit(limitBytes) + " is too little for tiles of " +
            std::to_string(kLeastTileSize) + " cells with their margin of " +
            markOption("max_hole") + " cells; give " +
            mebibytes(limitFor(tileBytes(kLeastTileSize, marginCells))) + " or more");
    return budget;
}

GdalCacheCap::GdalCacheCap(std::uint64_t bytes) : m_previous(GDALGetCacheMax64()) {
    GDALSetCacheMax64(std::min<GIntBig>(m_previous, static_cast<GIntBig>(bytes)));
}

GdalCacheCap::~GdalCacheCap() {
    GDALSetCacheMax64(m_previous);
}

} // namespace terratin::detail

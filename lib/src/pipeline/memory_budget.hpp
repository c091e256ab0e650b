#pragma once
/// @file
/// `--memory-limit`: how a tiled simplification shares its memory out. The limit
/// holds the process itself (code, GDAL, PROJ), GDAL's block cache, the writer's share (the
/// GeoPackage's index boxes, the vertices on tile sides) and the one tile being refined,
/// counted at its worst: every cell of it, margin included, a vertex of the TIN. The bytes
/// per cell are measured (docs/benchmarks.md, "Tiles in a memory limit").

#include <cstddef>
#include <cstdint>

namespace terratin::detail {

struct MemoryBudget {
    /// Cells a tile side: the largest that fits, or the one given.
    std::size_t tileSize = 0;
    /// At most this much for GDAL's block cache.
    std::uint64_t gdalCacheBytes = 0;
    /// What the writer may keep without passing the limit.
    std::uint64_t writerBytes = 0;
    /// What the tile in work may take; with MPI, rank 0 refines none and holds in it the
    /// tiles that came back before their turn.
    std::uint64_t tileBytes = 0;
};

/// The budget of `limitBytes` for tiles with a margin of `marginCells` (RefineOptions::maxHole,
/// 0 with fillHoles). `tileSize` 0: the largest tiles that fit, up to kMaxTileSize; else that
/// size, refused (InvalidInputError naming the least limit it needs) when it does not fit. A
/// limit too small for tiles of kLeastTileSize is refused, naming the least limit. `cellsMove`:
/// the tiles' cells lie at projected positions (TileOptions::cellPositions), which takes more
/// a cell.
MemoryBudget memoryBudget(std::uint64_t limitBytes, std::size_t marginCells, std::size_t tileSize,
                          bool cellsMove = false);

/// Holds GDAL's block cache to at most `bytes` while it lives: GDAL's default, 5 % of the
/// machine's memory, may pass a limit alone.
class GdalCacheCap {
public:
    explicit GdalCacheCap(std::uint64_t bytes);
    GdalCacheCap(const GdalCacheCap&) = delete;
    GdalCacheCap& operator=(const GdalCacheCap&) = delete;
    ~GdalCacheCap();

private:
    std::int64_t m_previous;
};

/// Tiles chosen from a memory limit are at least this many cells a side: smaller ones spend
/// more on their sides than they save.
inline constexpr std::size_t kLeastTileSize = 64;

} // namespace terratin::detail

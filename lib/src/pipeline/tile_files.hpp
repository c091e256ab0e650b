#pragma once
/// @file
/// `--tiles-dir`: each tile's TIN written to its own file as it is done, never
/// joined, and an index of the tiles' footprints. Internal to the build pipeline.

#include "../tile/tile_grid.hpp"
#include "tin_sink.hpp"

#include "terratin/geometry/height_grid.hpp"
#include "terratin/io/tile_index.hpp"
#include "terratin/io/tin_writer.hpp"
#include "terratin/triangulate/tin_mesh.hpp"

#include <cstddef>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace terratin::detail {

/// The files of one tiled build in a directory: `tile_ROW_COLUMN.EXT` (the format of
/// `writeOptions`, zero-padded numbers), and `tiles.gpkg`, the index. Until commit(), every
/// file it wrote is removed again on destruction (and the directory, if it made it), so a run
/// that fails leaves nothing behind.
class TileFiles final : public TinSink {
public:
    /// Checks, before anything is refined, that every file the tiles of a grid shaped like
    /// `extent`, cut in tiles of `tileSize`, may write can be written (an existing one only with
    /// writeOptions.overwrite), and makes the directory when it is missing. Throws IoError,
    /// InvalidInputError. `cellPositions`: where cells lie in the TIN's CRS when they move
    /// (TileOptions::cellPositions), for the footprints; empty: at their centres.
    TileFiles(std::filesystem::path directory, const HeightGrid& extent, std::size_t tileSize,
              io::TinWriteOptions writeOptions,
              std::function<std::vector<Point2>(const HeightGrid&)> cellPositions = {});
    TileFiles(const TileFiles&) = delete;
    TileFiles& operator=(const TileFiles&) = delete;
    ~TileFiles();

    /// Writes tile `tile` (row-major among the tiles); `vertexCells` as TinWriteOptions'
    /// (empty without a nodes layer). A tile left without a triangle (every one too long)
    /// gets no file.
    void write(std::size_t tile, TinMesh tin, std::vector<io::RasterCell> vertexCells) override;
    /// Writes the index of the tiles written, then keeps every file.
    io::TinWriteResult finish(const ProgressCallback& progress) override;

    [[nodiscard]] std::uint64_t points() const override { return m_points; }
    [[nodiscard]] std::uint64_t triangles() const override { return m_triangles; }
    [[nodiscard]] std::filesystem::path indexPath() const { return m_directory / "tiles.gpkg"; }

private:
    [[nodiscard]] std::string fileName(std::size_t tileRow, std::size_t tileColumn) const;
    void checkEveryFile() const;
    void removeWritten() noexcept;

    std::filesystem::path m_directory;
    HeightGrid m_extent;
    TileGrid m_tiles;
    int m_digits;
    io::TinWriteOptions m_writeOptions;
    std::function<std::vector<Point2>(const HeightGrid&)> m_cellPositions;
    bool m_madeDirectory = false;
    bool m_committed = false;
    std::vector<io::TileIndexEntry> m_entries;
    std::size_t m_points = 0;
    std::size_t m_triangles = 0;
    std::uint64_t m_features = 0;
};

} // namespace terratin::detail

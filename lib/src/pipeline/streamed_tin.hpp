#pragma once
/// @file
/// `--memory-limit`: a tiled build's TIN written to one file as its tiles are done,
/// never joined in memory. Its vertices are numbered as the joined TIN numbers them, so the file
/// holds the same TIN (a PLY the same bytes) as one written after joining. Internal to the
/// build pipeline.

#include "../io/tin_stream.hpp"
#include "../tile/joined_vertex_numbers.hpp"
#include "../tile/tile_grid.hpp"
#include "tin_sink.hpp"

#include "terratin/io/tin_writer.hpp"
#include "terratin/progress.hpp"
#include "terratin/triangulate/tin_mesh.hpp"

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string_view>
#include <vector>

namespace terratin::detail {

class StreamedTin final : public TinSink {
public:
    /// Opens `output` for the tiles of a grid of `width` x `height` cells cut in tiles of
    /// `tileSize` (see io::detail::openTinStream for what is checked and refused; `pieceBy`
    /// names the option that asked for it).
    StreamedTin(const std::filesystem::path& output, const io::TinWriteOptions& writeOptions,
                std::size_t width, std::size_t height, std::size_t tileSize,
                std::string_view pieceBy);

    /// Writes tile `tile` (row-major among the tiles, each once, in order), whose sourceIndex
    /// numbers the grid's cells; `vertexCells` as TinWriteOptions' (empty without a nodes
    /// layer).
    void write(std::size_t tile, TinMesh tin, std::vector<io::RasterCell> vertexCells) override;
    /// Completes the file and puts it in place.
    io::TinWriteResult finish(const ProgressCallback& progress) override;

    [[nodiscard]] std::uint64_t points() const override { return m_writer->vertexCount(); }
    [[nodiscard]] std::uint64_t triangles() const override { return m_writer->triangleCount(); }
    /// What the writer keeps until finish().
    [[nodiscard]] std::uint64_t heldBytes() const { return m_writer->heldBytes(); }

private:
    std::unique_ptr<io::detail::TinStreamWriter> m_writer;
    TileGrid m_tiles;
    JoinedVertexNumbers m_numbers;
};

} // namespace terratin::detail

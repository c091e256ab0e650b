#pragma once
/// @file
/// TinSink: where a build's TIN goes, a piece at a time. The whole file is one piece
/// (WholeFileSink); `--memory-limit` streams tiles into one file (StreamedTin); `--tiles-dir`
/// writes a file per tile and their index (TileFiles). BuildRun::deliver gives every piece the
/// same tail (long edges dropped, the nodes' raster cells) and BuildRun::close finishes any
/// sink the same way, so a new output is one more sink. Internal to the build pipeline.

#include "terratin/io/tin_writer.hpp"
#include "terratin/progress.hpp"
#include "terratin/triangulate/tin_mesh.hpp"

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <vector>

namespace terratin::detail {

class TinSink {
public:
    virtual ~TinSink() = default;

    /// Takes piece `piece` (a tile, row-major among the tiles, each once and in order; 0 for a
    /// whole TIN) whose vertices lie in the raster cells `vertexCells` (as TinWriteOptions';
    /// empty without a nodes layer).
    virtual void write(std::size_t piece, TinMesh tin, std::vector<io::RasterCell> vertexCells) = 0;
    /// After the last piece: completes the output and puts it in place; what was written.
    virtual io::TinWriteResult finish(const ProgressCallback& progress) = 0;

    /// The vertices and triangles taken so far.
    [[nodiscard]] virtual std::uint64_t points() const = 0;
    [[nodiscard]] virtual std::uint64_t triangles() const = 0;
};

/// The whole TIN as one file: its only piece is kept until finish() writes it (io::writeTin,
/// atomically, with `writeOptions` as they are then: the CRS and constrained edges the
/// producer set; finish() puts the piece's vertex cells in them, not copying the rest).
class WholeFileSink final : public TinSink {
public:
    WholeFileSink(std::filesystem::path output, io::TinWriteOptions& writeOptions);

    void write(std::size_t piece, TinMesh tin, std::vector<io::RasterCell> vertexCells) override;
    io::TinWriteResult finish(const ProgressCallback& progress) override;

    [[nodiscard]] std::uint64_t points() const override;
    [[nodiscard]] std::uint64_t triangles() const override;

private:
    std::filesystem::path m_output;
    io::TinWriteOptions* m_writeOptions;
    std::optional<TinMesh> m_tin;
    std::vector<io::RasterCell> m_vertexCells;
};

} // namespace terratin::detail

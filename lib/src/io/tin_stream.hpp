#pragma once
/// @file
/// One TIN file written piece by piece, as the tiles of a tiled build are done, so that memory
/// stays bounded: each piece's vertices and triangles go to disk at once, and only what the
/// file's end needs stays in memory (the GeoPackage's index boxes, GDAL's FlatGeobuf index
/// entries, a mesh format's counts and figures). Every format of writeTin
/// (gpkg/gpkg_tin_stream.hpp, ogr_tin_stream.hpp, mesh_stream.hpp).

#include "terratin/io/tin_writer.hpp"
#include "terratin/progress.hpp"
#include "terratin/triangulate/tin_mesh.hpp"

#include <cstdint>
#include <filesystem>
#include <memory>
#include <span>
#include <string_view>

namespace terratin::io::detail {

/// A piece of the TIN: a tile's TIN in its own vertex numbers.
struct TinPiece {
    const TinMesh* mesh = nullptr;
    /// numbers[v]: the whole TIN's number of the piece's vertex v. A vertex numbered at least
    /// the count of the vertices appended before is new, and the new vertices are numbered one
    /// after another in the piece's vertex order; the others came with earlier pieces.
    std::span<const std::uint32_t> numbers;
    /// The raster cell of each of the piece's vertices, or empty: a GeoPackage's nodes layer
    /// has row and col columns, NULL where a piece gives no cells.
    std::span<const RasterCell> cells;
};

class TinStreamWriter {
public:
    TinStreamWriter() = default;
    TinStreamWriter(const TinStreamWriter&) = delete;
    TinStreamWriter& operator=(const TinStreamWriter&) = delete;
    /// Without finish(), everything written is removed: no partial file is left.
    virtual ~TinStreamWriter() = default;

    /// Writes a piece. Throws IoError, InvalidInputError (a new vertex numbered out of turn).
    virtual void append(const TinPiece& piece) = 0;
    /// Completes the file and renames it into place. Throws IoError, Cancelled (by
    /// `progress`), InvalidInputError (no triangle was appended; an output that appeared
    /// during the run, without overwrite).
    virtual TinWriteResult finish(const ProgressCallback& progress) = 0;

    /// Bytes kept in memory until finish() (the GeoPackage's index boxes, the FlatGeobuf's
    /// index entries).
    [[nodiscard]] virtual std::uint64_t heldBytes() const { return 0; }
    [[nodiscard]] std::uint64_t vertexCount() const { return m_vertices; }
    [[nodiscard]] std::uint64_t triangleCount() const { return m_triangles; }

protected:
    /// Calls newVertex(v) for each new vertex v of the piece, in order, and counts the piece's
    /// vertices and triangles; InvalidInputError when a new vertex is numbered out of turn.
    template <class NewVertex> void countPiece(const TinPiece& piece, NewVertex&& newVertex) {
        for (std::size_t v = 0; v < piece.numbers.size(); ++v) {
            if (piece.numbers[v] < m_vertices)
                continue;
            if (piece.numbers[v] != m_vertices)
                throwOutOfTurn(piece.numbers[v]);
            newVertex(v);
            ++m_vertices;
        }
        m_triangles += piece.mesh->triangleCount();
    }

private:
    [[noreturn]] void throwOutOfTurn(std::uint32_t number) const;

    std::uint64_t m_vertices = 0;
    std::uint64_t m_triangles = 0;
};

/// Refuses (InvalidInputError, naming the options it marks, markOption) what a TIN written
/// piece by piece cannot be: with an edges layer (an edge's triangles may lie in two pieces),
/// appended to a GeoPackage (appendLayer); then what writeTin refuses of the options.
void checkTinStreamOptions(const TinWriteOptions& options, std::string_view pieceBy);

/// The writer of `output`, after the checks writeTin makes before its first byte (the
/// options, the CRS, the output and its location). `pieceBy` names, in messages, what cuts
/// the TIN in pieces ("--memory-limit").
std::unique_ptr<TinStreamWriter> openTinStream(const std::filesystem::path& output,
                                               const TinWriteOptions& options,
                                               std::string_view pieceBy);

} // namespace terratin::io::detail

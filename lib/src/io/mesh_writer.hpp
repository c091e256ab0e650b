#pragma once
/// @file
/// The mesh formats (PLY, 2DM, OBJ, LandXML) are each written by one description of their
/// file, a format class, and one driver that writes it either whole (writeTin: the TIN is at
/// hand, so the head's figures are taken first and every record goes straight to the file) or
/// piece by piece (openTinStream: the records go to two temporaries as the pieces come and are
/// joined under the head at the end; mesh_stream.hpp). Both give the same bytes. A new mesh
/// format is a writer file that defines its format class and its MeshWriter, and the format's
/// row in the table (tin_format.cpp) that points to that MeshWriter.
///
/// A format class, default-constructed once per file, has (MeshFormatBase gives the optional
/// ones, doing nothing):
///   kVertexMessage, kFaceMessage    the progress messages of its two loops
///   kVerticesAfterFigures           whether a vertex record depends on figures of the whole
///                                   TIN (OBJ's local origin): the records then wait, as raw
///                                   Point3, until every vertex has been seen twice
///   addVertex(p), addTriangle(a, b, c)   optional: the figures its head needs (LandXML's areas
///                                   and elevation range, OBJ's origin), every vertex then
///                                   every triangle in order (or piece by piece, in order)
///   recheckVertex(p)                optional: the second look at every vertex, in order, after
///                                   all were added (kVerticesAfterFigures)
///   head(file, info, vertexCount, triangleCount)   everything before the first vertex record
///   vertex(file, number, p)         the record of vertex `number` (from 0)
///   between(file)                   optional: what comes between the vertices and the faces
///   face(file, number, a, b, c)     the record of triangle `number` (from 0) of vertices a, b, c
///   trailer(file)                   optional: everything after the last face record

#include "buffered_file.hpp"
#include "mesh_stream.hpp"
#include "terratin/io/tin_writer.hpp"
#include "terratin/triangulate/tin_mesh.hpp"
#include "writer_support.hpp"

#include <cstdint>
#include <filesystem>
#include <memory>
#include <string_view>

namespace terratin::io::detail {

/// What a mesh format class needs not define: no figures, nothing between the vertices and
/// the faces, nothing after them.
struct MeshFormatBase {
    static constexpr bool kVerticesAfterFigures = false;
    void addVertex(const Point3&) {}
    void addTriangle(const Point3&, const Point3&, const Point3&) {}
    void recheckVertex(const Point3&) {}
    void between(BufferedFile&) {}
    void trailer(BufferedFile&) {}
};

/// A mesh format's two ways of being written, which its row of the format table points to.
struct MeshWriter {
    /// Writes the whole file of `mesh` (checked by writeTin) to `file`, ticking `ticker` over
    /// its records; returns vertices + triangles. Throws IoError, Cancelled, InvalidInputError
    /// (a mesh the format cannot hold).
    std::uint64_t (*writeWhole)(const TinMesh& mesh, const MeshFileInfo& info, BufferedFile& file,
                                const ProgressTicker& ticker);
    /// The writer of `output` piece by piece (openTinStream has made its checks).
    std::unique_ptr<TinStreamWriter> (*openStream)(const std::filesystem::path& output,
                                                   const TinWriteOptions& options);
};

/// The MeshWriter of `format`'s row in the format table (tin_format.cpp); InvalidInputError
/// for a vector format, which OGR writes.
const MeshWriter& meshWriterOf(TinFormat format);

/// MeshWriter::writeWhole of format class `Format`.
template <class Format>
std::uint64_t writeWholeMesh(const TinMesh& mesh, const MeshFileInfo& info, BufferedFile& file,
                             const ProgressTicker& ticker) {
    const std::uint64_t vertexCount = mesh.vertexCount();
    const std::uint64_t triangleCount = mesh.triangleCount();
    const auto corner = [&](std::uint64_t t, int i) { return mesh.triangles[3 * t + i]; };
    Format format;
    for (const Point3& p : mesh.vertices)
        format.addVertex(p);
    for (std::uint64_t t = 0; t < triangleCount; ++t)
        format.addTriangle(mesh.vertices[corner(t, 0)], mesh.vertices[corner(t, 1)],
                           mesh.vertices[corner(t, 2)]);
    if constexpr (Format::kVerticesAfterFigures)
        for (const Point3& p : mesh.vertices)
            format.recheckVertex(p);
    format.head(file, info, vertexCount, triangleCount);
    for (std::uint64_t v = 0; v < vertexCount; ++v) {
        ticker.tick(v, Format::kVertexMessage);
        format.vertex(file, v, mesh.vertices[v]);
    }
    format.between(file);
    for (std::uint64_t t = 0; t < triangleCount; ++t) {
        ticker.tick(vertexCount + t, Format::kFaceMessage);
        format.face(file, t, corner(t, 0), corner(t, 1), corner(t, 2));
    }
    format.trailer(file);
    return vertexCount + triangleCount;
}

/// The stream writer of format class `Format`: MeshStreamBase's temporaries and join, with
/// the format's records.
template <class Format> class MeshStreamWriter final : public MeshStreamBase {
public:
    using MeshStreamBase::MeshStreamBase;

    void append(const TinPiece& piece) override {
        const TinMesh& mesh = *piece.mesh;
        BufferedFile& vertices = vertexRecords();
        BufferedFile& faces = faceRecords();
        const std::uint64_t firstTriangle = triangleCount();
        std::uint64_t number = vertexCount();
        countPiece(piece, [&](std::size_t v) {
            const Point3& p = mesh.vertices[v];
            m_format.addVertex(p);
            if constexpr (Format::kVerticesAfterFigures)
                vertices.bytes(&p, sizeof p);
            else
                m_format.vertex(vertices, number, p);
            ++number;
        });
        for (std::size_t t = 0; t < mesh.triangleCount(); ++t) {
            const std::uint32_t* corner = &mesh.triangles[3 * t];
            m_format.addTriangle(mesh.vertices[corner[0]], mesh.vertices[corner[1]],
                                 mesh.vertices[corner[2]]);
            m_format.face(faces, firstTriangle + t, piece.numbers[corner[0]],
                          piece.numbers[corner[1]], piece.numbers[corner[2]]);
        }
    }

    TinWriteResult finish(const ProgressCallback& progress) override {
        constexpr int kVertexReads = Format::kVerticesAfterFigures ? 2 : 1;
        return join(progress, kVertexReads, [&](MeshJoin& joined) {
            BufferedFile& file = joined.file();
            if constexpr (Format::kVerticesAfterFigures)
                joined.eachStoredVertex([&](const Point3& p) { m_format.recheckVertex(p); });
            m_format.head(file, info(), vertexCount(), triangleCount());
            if constexpr (Format::kVerticesAfterFigures) {
                std::uint64_t number = 0;
                joined.eachStoredVertex(
                    [&](const Point3& p) { m_format.vertex(file, number++, p); });
            } else {
                joined.copyVertexRecords();
            }
            m_format.between(file);
            joined.copyFaceRecords();
            m_format.trailer(file);
        });
    }

private:
    Format m_format;
};

/// The MeshWriter of format class `Format`, for its writer file to define.
template <class Format> constexpr MeshWriter meshWriterFor() {
    return {&writeWholeMesh<Format>,
            [](const std::filesystem::path& output,
               const TinWriteOptions& options) -> std::unique_ptr<TinStreamWriter> {
                return std::make_unique<MeshStreamWriter<Format>>(output, options);
            }};
}

} // namespace terratin::io::detail

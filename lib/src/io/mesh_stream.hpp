#pragma once
/// @file
/// What the mesh formats' TinStreamWriter (mesh_writer.hpp's MeshStreamWriter) shares: each
/// piece's vertex and face records go to two temporaries beside the output as they come, and
/// finish() writes the file from them under the head, which needs what only the whole TIN
/// gives (PLY's counts, LandXML's areas and elevation range, OBJ's local origin: its vertices
/// are kept as raw Point3 and their records written then). The file is the one writeTin
/// writes of the whole TIN.

#include "atomic_output.hpp"
#include "buffered_file.hpp"
#include "tin_stream.hpp"
#include "writer_support.hpp"

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string_view>

namespace terratin::io::detail {

/// Preconditions are checked by openTinStream.
std::unique_ptr<TinStreamWriter> openMeshTinStream(const std::filesystem::path& output,
                                                   const TinWriteOptions& options);

/// The file finish() writes, and the two temporaries it is made of. Reading them back reports
/// progress ("Joining vertices and faces") after each chunk, so that a cancel reaches a long
/// join.
class MeshJoin {
public:
    MeshJoin(BufferedFile& file, std::string_view stage, const ProgressCallback& progress,
             const std::filesystem::path& output, const std::filesystem::path& vertices,
             const std::filesystem::path& faces, int vertexReads);

    [[nodiscard]] BufferedFile& file() { return m_file; }
    /// The vertex records, or the face records, as they were written.
    void copyVertexRecords() { copy(m_vertices); }
    void copyFaceRecords() { copy(m_faces); }
    /// Calls `point(p)` for each Point3 of the vertex temporary, in order, when it holds raw
    /// Point3 (kVerticesAfterFigures).
    template <class EachPoint> void eachStoredVertex(EachPoint&& point) {
        std::array<char, sizeof(Point3)> partial{};
        std::size_t held = 0; // bytes of a record cut by a chunk's end
        readBack(m_vertices, [&](const char* data, std::size_t size) {
            for (std::size_t at = 0; at < size;) {
                const std::size_t take = std::min(sizeof(Point3) - held, size - at);
                std::memcpy(partial.data() + held, data + at, take);
                held += take;
                at += take;
                if (held == sizeof(Point3)) {
                    Point3 p;
                    std::memcpy(&p, partial.data(), sizeof p);
                    point(p);
                    held = 0;
                }
            }
        });
    }

private:
    using Chunk = std::function<void(const char* data, std::size_t size)>;
    void copy(const std::filesystem::path& from);
    /// Reads `from` (written by this run) in chunks, handing each to `chunk`; IoError naming
    /// the output when reading fails, Cancelled when progress says stop.
    void readBack(const std::filesystem::path& from, const Chunk& chunk);

    BufferedFile& m_file;
    std::string_view m_stage;
    const ProgressCallback& m_progress;
    const std::filesystem::path& m_output;
    std::filesystem::path m_vertices;
    std::filesystem::path m_faces;
    /// Bytes to read back in all (the vertex temporary `vertexReads` times, the faces once),
    /// and read so far.
    std::uint64_t m_planned = 0;
    std::uint64_t m_done = 0;
};

/// A mesh format's stream writer but for the records: the temporaries, the file's facts, the
/// join.
class MeshStreamBase : public TinStreamWriter {
public:
    MeshStreamBase(std::filesystem::path output, const TinWriteOptions& options);

protected:
    [[nodiscard]] BufferedFile& vertexRecords() { return *m_vertices; }
    [[nodiscard]] BufferedFile& faceRecords() { return *m_faces; }
    [[nodiscard]] const MeshFileInfo& info() const { return m_info; }
    /// Refuses a TIN without triangles, closes the temporaries, and writes the file with
    /// `write` (its vertex temporary read `vertexReads` times), then puts it in place.
    TinWriteResult join(const ProgressCallback& progress, int vertexReads,
                        const std::function<void(MeshJoin&)>& write);

private:
    std::string_view m_stage;
    std::filesystem::path m_output;
    AtomicOutput m_temporaries;
    std::filesystem::path m_vertexPath;
    std::filesystem::path m_facePath;
    MeshFileInfo m_info;
    std::optional<BufferedFile> m_vertices;
    std::optional<BufferedFile> m_faces;
};

} // namespace terratin::io::detail

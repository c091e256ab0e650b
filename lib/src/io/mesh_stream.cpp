#include "mesh_stream.hpp"

#include "atomic_output.hpp"
#include "buffered_file.hpp"
#include "landxml_writer.hpp"
#include "obj_writer.hpp"
#include "ply_writer.hpp"
#include "terratin/error.hpp"
#include "two_dm_writer.hpp"
#include "writer_support.hpp"

#include <array>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <optional>
#include <string>
#include <vector>

namespace terratin::io::detail {

namespace fs = std::filesystem;

namespace {

/// Reads file `from` (written by this run) in chunks, handing each to `chunk(data, size)`;
/// IoError naming `display` when reading fails.
template <class Chunk>
void readBack(std::string_view stage, const fs::path& from, const fs::path& display,
              Chunk&& chunk) {
    constexpr std::size_t kChunkBytes = std::size_t{1} << 20;
    std::FILE* in = std::fopen(from.c_str(), "rb");
    if (in == nullptr)
        throw IoError(std::string(stage) + ": cannot read back the part of " + quoted(display) +
                      " written so far: " + std::strerror(errno));
    std::vector<char> buffer(kChunkBytes);
    std::size_t read = 0;
    while ((read = std::fread(buffer.data(), 1, buffer.size(), in)) > 0)
        chunk(buffer.data(), read);
    const bool failed = std::ferror(in) != 0;
    std::fclose(in);
    if (failed)
        throw IoError(std::string(stage) + ": cannot read back the part of " + quoted(display) +
                      " written so far");
}

void appendFile(std::string_view stage, BufferedFile& out, const fs::path& from,
                const fs::path& display) {
    readBack(stage, from, display,
             [&](const char* data, std::size_t size) { out.bytes(data, size); });
}

/// Calls `point(p)` for each Point3 of a file of raw Point3 records.
template <class EachPoint>
void forEachStoredPoint(std::string_view stage, const fs::path& from, const fs::path& display,
                        EachPoint&& point) {
    std::array<char, sizeof(Point3)> partial{};
    std::size_t held = 0; // bytes of a record cut by a chunk's end
    readBack(stage, from, display, [&](const char* data, std::size_t size) {
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

/// Where the records go and what finish() writes around them.
struct MeshTemporaries {
    std::string_view stage;
    fs::path output;
    fs::path vertices;
    fs::path faces;
};

/// A format's records, written as the pieces come, and its file, written at the end.
class MeshRecords {
public:
    virtual ~MeshRecords() = default;
    /// The TIN's vertex `number` (from 0).
    virtual void vertex(BufferedFile& vertices, std::uint64_t number, const Point3& p) = 0;
    /// The TIN's triangle `number` (from 0) of vertices `corners`, at `at`.
    virtual void triangle(BufferedFile& faces, std::uint64_t number,
                          const std::array<std::uint32_t, 3>& corners,
                          const std::array<Point3, 3>& at) = 0;
    /// The whole file, from the two temporaries.
    virtual void join(BufferedFile& out, const MeshFileInfo& info, const MeshTemporaries& files,
                      std::uint64_t vertexCount, std::uint64_t triangleCount) = 0;
};

class PlyRecords final : public MeshRecords {
public:
    void vertex(BufferedFile& vertices, std::uint64_t, const Point3& p) override {
        putPlyVertex(vertices, p);
    }
    void triangle(BufferedFile& faces, std::uint64_t, const std::array<std::uint32_t, 3>& corners,
                  const std::array<Point3, 3>&) override {
        putPlyFace(faces, corners[0], corners[1], corners[2]);
    }
    void join(BufferedFile& out, const MeshFileInfo& info, const MeshTemporaries& files,
              std::uint64_t vertexCount, std::uint64_t triangleCount) override {
        out.text(plyHeader(info, vertexCount, triangleCount));
        appendFile(files.stage, out, files.vertices, files.output);
        appendFile(files.stage, out, files.faces, files.output);
    }
};

class TwoDmRecords final : public MeshRecords {
public:
    void vertex(BufferedFile& vertices, std::uint64_t number, const Point3& p) override {
        putTwoDmNode(vertices, number, p);
    }
    void triangle(BufferedFile& faces, std::uint64_t number,
                  const std::array<std::uint32_t, 3>& corners,
                  const std::array<Point3, 3>&) override {
        putTwoDmElement(faces, number, corners[0], corners[1], corners[2]);
    }
    void join(BufferedFile& out, const MeshFileInfo& info, const MeshTemporaries& files,
              std::uint64_t, std::uint64_t) override {
        putTwoDmHead(out, info);
        appendFile(files.stage, out, files.vertices, files.output);
        appendFile(files.stage, out, files.faces, files.output);
    }
};

class LandXmlRecords final : public MeshRecords {
public:
    void vertex(BufferedFile& vertices, std::uint64_t number, const Point3& p) override {
        putLandXmlPoint(vertices, number, p);
        m_surface.addVertex(p);
    }
    void triangle(BufferedFile& faces, std::uint64_t, const std::array<std::uint32_t, 3>& corners,
                  const std::array<Point3, 3>& at) override {
        putLandXmlFace(faces, corners[0], corners[1], corners[2]);
        m_surface.addTriangle(at[0], at[1], at[2]);
    }
    void join(BufferedFile& out, const MeshFileInfo& info, const MeshTemporaries& files,
              std::uint64_t, std::uint64_t) override {
        putLandXmlHead(out, info, m_surface);
        appendFile(files.stage, out, files.vertices, files.output);
        out.text(kLandXmlBetween);
        appendFile(files.stage, out, files.faces, files.output);
        out.text(kLandXmlEnd);
    }

private:
    LandXmlSurface m_surface;
};

/// OBJ writes its vertices relative to an origin that depends on all of them: they wait as
/// raw doubles.
class ObjRecords final : public MeshRecords {
public:
    void vertex(BufferedFile& vertices, std::uint64_t, const Point3& p) override {
        vertices.bytes(&p, sizeof p);
        m_origin.see(p);
    }
    void triangle(BufferedFile& faces, std::uint64_t, const std::array<std::uint32_t, 3>& corners,
                  const std::array<Point3, 3>&) override {
        putObjFace(faces, corners[0], corners[1], corners[2]);
    }
    void join(BufferedFile& out, const MeshFileInfo& info, const MeshTemporaries& files,
              std::uint64_t vertexCount, std::uint64_t triangleCount) override {
        forEachStoredPoint(files.stage, files.vertices, files.output,
                           [&](const Point3& p) { m_origin.check(p); });
        const Point3 origin = m_origin.origin();
        putObjHead(out, info, vertexCount, triangleCount, origin);
        forEachStoredPoint(files.stage, files.vertices, files.output,
                           [&](const Point3& p) { putObjVertex(out, p, origin); });
        appendFile(files.stage, out, files.faces, files.output);
    }

private:
    ObjOrigin m_origin;
};

std::unique_ptr<MeshRecords> recordsOf(TinFormat format) {
    switch (format) {
    case TinFormat::Ply:
        return std::make_unique<PlyRecords>();
    case TinFormat::TwoDm:
        return std::make_unique<TwoDmRecords>();
    case TinFormat::LandXml:
        return std::make_unique<LandXmlRecords>();
    case TinFormat::Obj:
        return std::make_unique<ObjRecords>();
    default:
        throw InvalidInputError("TinWriter: not a mesh format");
    }
}

class MeshStreamWriter final : public TinStreamWriter {
public:
    MeshStreamWriter(fs::path output, const TinWriteOptions& options)
        : m_records(recordsOf(options.format)), m_stage(writerStage(options.format)),
          m_output(std::move(output)),
          m_temporaries(m_stage, m_output, existingTargetFor(options.overwrite),
                        options.optionName),
          m_files{m_stage, m_output, m_temporaries.temporary(".vtx"),
                  m_temporaries.temporary(".fac")} {
        m_info.name = options.layerName;
        m_info.crs = summariseCrs(m_stage, options.crsWkt);
        m_info.softwareVersion = options.softwareVersion;
        m_vertices.emplace(m_stage, m_files.vertices, m_output);
        m_faces.emplace(m_stage, m_files.faces, m_output);
    }

    void append(const TinPiece& piece) override {
        const TinMesh& mesh = *piece.mesh;
        const std::uint64_t firstTriangle = triangleCount();
        std::uint64_t number = vertexCount();
        countPiece(piece, [&](std::size_t v) {
            m_records->vertex(*m_vertices, number++, mesh.vertices[v]);
        });
        for (std::size_t t = 0; t < mesh.triangleCount(); ++t) {
            const std::uint32_t* corner = &mesh.triangles[3 * t];
            m_records->triangle(
                *m_faces, firstTriangle + t,
                {piece.numbers[corner[0]], piece.numbers[corner[1]], piece.numbers[corner[2]]},
                {mesh.vertices[corner[0]], mesh.vertices[corner[1]], mesh.vertices[corner[2]]});
        }
    }

    TinWriteResult finish(const ProgressCallback& progress) override {
        if (triangleCount() == 0)
            throw InvalidInputError(std::string(m_stage) +
                                    ": the mesh has no triangles; nothing written to " +
                                    quoted(m_output));
        m_vertices->close();
        m_faces->close();
        reportProgress(m_stage, progress, 0.0, "Joining vertices and faces", m_output);
        const fs::path joined = m_temporaries.temporary(m_output.extension().string());
        {
            BufferedFile file(m_stage, joined, m_output);
            m_records->join(file, m_info, m_files, vertexCount(), triangleCount());
            // The last chance to cancel: nothing is in place before it.
            reportProgress(m_stage, progress, 0.98, "Finishing", m_output);
            file.close();
        }
        m_temporaries.commit(joined, m_output);
        return {vertexCount() + triangleCount()};
    }

private:
    std::unique_ptr<MeshRecords> m_records;
    std::string_view m_stage;
    fs::path m_output;
    AtomicOutput m_temporaries;
    MeshTemporaries m_files;
    MeshFileInfo m_info;
    std::optional<BufferedFile> m_vertices;
    std::optional<BufferedFile> m_faces;
};

} // namespace

std::unique_ptr<TinStreamWriter> openMeshTinStream(const fs::path& output,
                                                   const TinWriteOptions& options) {
    return std::make_unique<MeshStreamWriter>(output, options);
}

} // namespace terratin::io::detail

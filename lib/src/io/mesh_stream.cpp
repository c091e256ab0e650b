#include "mesh_stream.hpp"

#include "mesh_writer.hpp"
#include "terratin/error.hpp"

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <string>
#include <system_error>
#include <vector>

namespace terratin::io::detail {

namespace fs = std::filesystem;

namespace {

/// Share of the progress range for the join; the rest is flushing and the rename.
constexpr double kJoinShare = 0.98;

constexpr std::string_view kJoinMessage = "Joining vertices and faces";

std::uint64_t sizeOf(const fs::path& file) {
    std::error_code error;
    const std::uintmax_t size = fs::file_size(file, error);
    return error ? 0 : size;
}

} // namespace

MeshJoin::MeshJoin(BufferedFile& file, std::string_view stage, const ProgressCallback& progress,
                   const fs::path& output, const fs::path& vertices, const fs::path& faces,
                   int vertexReads)
    : m_file(file), m_stage(stage), m_progress(progress), m_output(output), m_vertices(vertices),
      m_faces(faces),
      m_planned(static_cast<std::uint64_t>(vertexReads) * sizeOf(vertices) + sizeOf(faces)) {}

void MeshJoin::copy(const fs::path& from) {
    readBack(from, [&](const char* data, std::size_t size) { m_file.bytes(data, size); });
}

void MeshJoin::readBack(const fs::path& from, const Chunk& chunk) {
    constexpr std::size_t kChunkBytes = std::size_t{1} << 20;
    std::FILE* in = std::fopen(from.c_str(), "rb");
    if (in == nullptr)
        throw IoError(std::string(m_stage) + ": cannot read back the part of " + quoted(m_output) +
                      " written so far: " + std::strerror(errno));
    std::vector<char> buffer(kChunkBytes);
    std::size_t read = 0;
    try {
        while ((read = std::fread(buffer.data(), 1, buffer.size(), in)) > 0) {
            chunk(buffer.data(), read);
            m_done += read;
            const double done =
                m_planned == 0 ? 1.0 : static_cast<double>(m_done) / static_cast<double>(m_planned);
            reportProgress(m_stage, m_progress, kJoinShare * std::min(done, 1.0), kJoinMessage,
                           m_output);
        }
    } catch (...) {
        std::fclose(in);
        throw;
    }
    const bool failed = std::ferror(in) != 0;
    std::fclose(in);
    if (failed)
        throw IoError(std::string(m_stage) + ": cannot read back the part of " + quoted(m_output) +
                      " written so far");
}

MeshStreamBase::MeshStreamBase(fs::path output, const TinWriteOptions& options)
    : m_stage(writerStage(options.format)), m_output(std::move(output)),
      m_temporaries(m_stage, m_output, existingTargetFor(options.overwrite)),
      m_vertexPath(m_temporaries.temporary(".vtx")), m_facePath(m_temporaries.temporary(".fac")) {
    m_info.name = options.layerName;
    m_info.crs = summariseCrs(m_stage, options.crsWkt);
    m_info.softwareVersion = options.softwareVersion;
    m_vertices.emplace(m_stage, m_vertexPath, m_output);
    m_faces.emplace(m_stage, m_facePath, m_output);
}

TinWriteResult MeshStreamBase::join(const ProgressCallback& progress, int vertexReads,
                                    const std::function<void(MeshJoin&)>& write) {
    if (triangleCount() == 0)
        throw InvalidInputError(std::string(m_stage) +
                                ": the mesh has no triangles; nothing written to " +
                                quoted(m_output));
    m_vertices->close();
    m_faces->close();
    reportProgress(m_stage, progress, 0.0, kJoinMessage, m_output);
    const fs::path joined = m_temporaries.temporary(m_output.extension().string());
    {
        BufferedFile file(m_stage, joined, m_output);
        MeshJoin parts(file, m_stage, progress, m_output, m_vertexPath, m_facePath, vertexReads);
        write(parts);
        // The last chance to cancel: nothing is in place before it.
        reportProgress(m_stage, progress, kJoinShare, "Finishing", m_output);
        file.close();
    }
    m_temporaries.commit(joined, m_output);
    return {vertexCount() + triangleCount()};
}

std::unique_ptr<TinStreamWriter> openMeshTinStream(const fs::path& output,
                                                   const TinWriteOptions& options) {
    return meshWriterOf(options.format).openStream(output, options);
}

} // namespace terratin::io::detail

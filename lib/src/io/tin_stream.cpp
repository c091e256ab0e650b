#include "tin_stream.hpp"

#include "atomic_output.hpp"
#include "buffered_file.hpp"
#include "gpkg/gpkg_tin_stream.hpp"
#include "ogr_dataset_support.hpp"
#include "ogr_tin_stream.hpp"
#include "ogr_tin_writer.hpp"
#include "ply_writer.hpp"
#include "style_beside.hpp"
#include "terratin/error.hpp"
#include "terratin/gdal_error.hpp"
#include "writer_support.hpp"

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <limits>
#include <optional>
#include <string>
#include <vector>

namespace terratin::io::detail {

namespace fs = std::filesystem;

namespace {

constexpr std::string_view kPlyStage = "PlyWriter";

/// Appends the bytes of file `from` to `out`; IoError naming `display` when reading fails.
void appendFileTo(BufferedFile& out, const fs::path& from, const fs::path& display) {
    constexpr std::size_t kChunkBytes = 1 << 20;
    std::FILE* in = std::fopen(from.c_str(), "rb");
    if (in == nullptr)
        throw IoError(std::string(kPlyStage) + ": cannot read back the part of " + quoted(display) +
                      " written so far: " + std::strerror(errno));
    std::vector<char> chunk(kChunkBytes);
    std::size_t read = 0;
    while ((read = std::fread(chunk.data(), 1, chunk.size(), in)) > 0)
        out.bytes(chunk.data(), read);
    const bool failed = std::ferror(in) != 0;
    std::fclose(in);
    if (failed)
        throw IoError(std::string(kPlyStage) + ": cannot read back the part of " + quoted(display) +
                      " written so far");
}

/// A binary PLY written piece by piece: the vertices and the faces go to two temporaries as
/// they come; finish() writes the header, which needs both counts, and the two after it.
class PlyStreamWriter final : public TinStreamWriter {
public:
    PlyStreamWriter(fs::path output, const TinWriteOptions& options)
        : m_output(std::move(output)),
          m_temporaries(kPlyStage, m_output, existingTargetFor(options.overwrite),
                        options.optionName),
          m_vertexPath(m_temporaries.temporary(".plv")),
          m_facePath(m_temporaries.temporary(".plf")) {
        m_info.name = options.layerName;
        m_info.crs = summariseCrs(kPlyStage, options.crsWkt);
        m_info.softwareVersion = options.softwareVersion;
        m_vertices.emplace(kPlyStage, m_vertexPath, m_output);
        m_faces.emplace(kPlyStage, m_facePath, m_output);
    }

    void append(const TinPiece& piece) override {
        countPiece(piece,
                   [&](std::size_t v) { putPlyVertex(*m_vertices, piece.mesh->vertices[v]); });
        const auto& corners = piece.mesh->triangles;
        for (std::size_t i = 0; i < corners.size(); i += 3)
            putPlyFace(*m_faces, piece.numbers[corners[i]], piece.numbers[corners[i + 1]],
                       piece.numbers[corners[i + 2]]);
    }

    TinWriteResult finish(const ProgressCallback& progress) override {
        if (triangleCount() == 0)
            throw InvalidInputError(std::string(kPlyStage) +
                                    ": the mesh has no triangles; nothing written to " +
                                    quoted(m_output));
        const std::string header = plyHeader(m_info, vertexCount(), triangleCount());
        m_vertices->close();
        m_faces->close();
        reportProgress(kPlyStage, progress, 0.0, "Joining vertices and faces", m_output);
        const fs::path joined = m_temporaries.temporary(".ply");
        {
            BufferedFile file(kPlyStage, joined, m_output);
            file.text(header);
            appendFileTo(file, m_vertexPath, m_output);
            appendFileTo(file, m_facePath, m_output);
            // The last chance to cancel: nothing is in place before it.
            reportProgress(kPlyStage, progress, 0.98, "Finishing", m_output);
            file.close();
        }
        m_temporaries.commit(joined, m_output);
        return {vertexCount() + triangleCount()};
    }

private:
    fs::path m_output;
    AtomicOutput m_temporaries;
    fs::path m_vertexPath;
    fs::path m_facePath;
    MeshFileInfo m_info;
    std::optional<BufferedFile> m_vertices;
    std::optional<BufferedFile> m_faces;
};

/// --qgis-style around a writer of a vector format: the elevations' range followed as the
/// pieces come, the style put beside the data once it is in place (style_beside.hpp).
class StyledStreamWriter final : public TinStreamWriter {
public:
    StyledStreamWriter(std::unique_ptr<TinStreamWriter> data, const fs::path& output,
                       const TinWriteOptions& options)
        : m_style(kOgrStage, output, ogrOutputFiles(output, options.format), options),
          m_data(std::move(data)) {}

    void append(const TinPiece& piece) override {
        countPiece(piece, [&](std::size_t v) {
            m_lowest = std::min(m_lowest, piece.mesh->vertices[v].z);
            m_highest = std::max(m_highest, piece.mesh->vertices[v].z);
        });
        m_data->append(piece);
    }

    TinWriteResult finish(const ProgressCallback& progress) override {
        if (triangleCount() > 0)
            m_style.write(m_lowest, m_highest);
        const TinWriteResult result = m_data->finish(progress);
        m_style.commit();
        return result;
    }

    [[nodiscard]] std::uint64_t heldBytes() const override { return m_data->heldBytes(); }

private:
    StyleBeside m_style;
    std::unique_ptr<TinStreamWriter> m_data;
    double m_lowest = std::numeric_limits<double>::infinity();
    double m_highest = -std::numeric_limits<double>::infinity();
};

std::unique_ptr<TinStreamWriter> openDataStream(const fs::path& output,
                                                const TinWriteOptions& options) {
    switch (options.format) {
    case TinFormat::Ply:
        return std::make_unique<PlyStreamWriter>(output, options);
    case TinFormat::GeoPackage:
        return openGpkgTinStream(output, options);
    default:
        return openOgrTinStream(output, options);
    }
}

} // namespace

void TinStreamWriter::throwOutOfTurn(std::uint32_t number) const {
    throw InvalidInputError("TinWriter: a piece's new vertex is numbered " +
                            std::to_string(number) + ", not " + std::to_string(m_vertices));
}

void checkTinStreamOptions(const TinWriteOptions& options, std::string_view pieceBy) {
    const auto refuse = [&](const std::string& what) {
        throw InvalidInputError(std::string(pieceBy) + " writes the TIN tile by tile, " + what);
    };
    if (!isOgrFormat(options.format) && options.format != TinFormat::Ply)
        refuse("to a GeoPackage, Shapefile, FlatGeobuf or PLY only (or one file a tile with " +
               options.optionName("tiles_dir") + ")");
    if (options.edges)
        refuse("without " + options.optionName("edges") +
               " (an edge's triangles may lie in two tiles)");
    if (options.appendLayer)
        refuse("to a new file, not with " + options.optionName("append_layer"));
    checkTinWriteOptions(options);
}

std::unique_ptr<TinStreamWriter>
openTinStream(const fs::path& output, const TinWriteOptions& options, std::string_view pieceBy) {
    initialiseGdal();
    checkTinStreamOptions(options, pieceBy);
    checkTinOutput(output, options);
    std::unique_ptr<TinStreamWriter> data = openDataStream(output, options);
    if (!options.qgisStyle)
        return data;
    return std::make_unique<StyledStreamWriter>(std::move(data), output, options);
}

} // namespace terratin::io::detail

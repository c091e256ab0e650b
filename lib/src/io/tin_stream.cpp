#include "tin_stream.hpp"

#include "gpkg/gpkg_tin_stream.hpp"
#include "mesh_stream.hpp"
#include "ogr_dataset_support.hpp"
#include "ogr_tin_stream.hpp"
#include "ogr_tin_writer.hpp"
#include "style_beside.hpp"
#include "terratin/error.hpp"
#include "terratin/gdal_error.hpp"

#include <algorithm>
#include <limits>
#include <string>

namespace terratin::io::detail {

namespace fs = std::filesystem;

namespace {

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
    if (options.format == TinFormat::GeoPackage)
        return openGpkgTinStream(output, options);
    if (isOgrFormat(options.format))
        return openOgrTinStream(output, options);
    return openMeshTinStream(output, options);
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
    if (options.edges)
        refuse("without " + markOption("edges") + " (an edge's triangles may lie in two tiles)");
    if (options.appendLayer)
        refuse("to a new file, not with " + markOption("append_layer"));
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

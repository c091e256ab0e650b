#include "ogr_tin_stream.hpp"

#include "atomic_output.hpp"
#include "ogr_dataset_support.hpp"
#include "ogr_tin_writer.hpp"
#include "ogr_triangle_layer.hpp"
#include "terratin/error.hpp"
#include "writer_support.hpp"

#include <optional>
#include <string>

namespace terratin::io::detail {

namespace fs = std::filesystem;

namespace {

/// What GDAL 3.6's FlatGeobuf writer keeps per feature until the file is closed: a shared
/// index item (a box, the feature's size and offset) and its pointer, the box copied again
/// into the packed tree built on close. Peak RSS grows by about 90 bytes a triangle with the
/// index (docs/benchmarks.md).
constexpr std::uint64_t kFgbIndexBytesPerFeature = 96;

/// Triangle `t` of `mesh` alone.
TinMesh triangleOf(const TinMesh& mesh, std::size_t t) {
    TinMesh one;
    for (int corner = 0; corner < 3; ++corner)
        one.vertices.push_back(mesh.vertices[mesh.triangles[3 * t + corner]]);
    one.triangles = {0, 1, 2};
    return one;
}

class OgrStreamWriter final : public TinStreamWriter {
public:
    OgrStreamWriter(fs::path output, const TinWriteOptions& options)
        : m_output(std::move(output)), m_options(options),
          m_shapefile(options.format == TinFormat::Shapefile),
          m_temporaries(kOgrStage, m_output, existingTargetFor(options.overwrite)),
          m_srs(parseOutputCrs(options.crsWkt)), m_pieceTicker(kOgrStage, {}, m_output, 0, 0, 1) {
        m_file = m_shapefile ? makeShapefileDirectory(m_temporaries, m_output)
                             : m_temporaries.temporary(".fgb");
        m_dataset = createDataset(m_shapefile ? "ESRI Shapefile" : "FlatGeobuf", m_file, m_output);
        m_layer = &createTriangleLayer(*m_dataset, {m_output.stem().string(), options.format},
                                       m_srs, options, m_output);
    }

    void append(const TinPiece& piece) override {
        countPiece(piece, [](std::size_t) {});
        const TinMesh& mesh = *piece.mesh;
        if (mesh.triangleCount() == 0)
            return;
        if (!m_shapefile) {
            writeTriangles(*m_layer, mesh, m_options, m_pieceTicker, m_output);
            return;
        }
        // The size is known only now: refused as soon as it passes the format's limit.
        checkShapefileLimits(triangleCount(), m_options.attributes, m_output);
        // The TIN's last triangle goes in with the DBF end mark (ogr_tin_writer.cpp says
        // why): each piece's last waits for the next piece, or for finish().
        if (m_held)
            writeTriangles(*m_layer, *m_held, m_options, m_pieceTicker, m_output);
        writeTriangles(*m_layer, mesh, m_options, m_pieceTicker, m_output,
                       {0, mesh.triangleCount() - 1});
        m_held = triangleOf(mesh, mesh.triangleCount() - 1);
    }

    TinWriteResult finish(const ProgressCallback& progress) override {
        if (triangleCount() == 0)
            throw InvalidInputError(std::string(kOgrStage) +
                                    ": the mesh has no triangles; nothing written to " +
                                    quoted(m_output));
        const ProgressTicker ticker(kOgrStage, progress, m_output, 0.0, 0.98, 1);
        const bool index = !m_shapefile && m_options.spatialIndex;
        ticker.report(0, index ? "Building spatial index" : "Finishing");
        closeDataset(m_dataset, m_output); // FlatGeobuf: GDAL builds the index now
        if (m_shapefile)
            appendLastTriangle(*m_held, m_file, m_options, ticker, m_output);
        ticker.report(1, "Finishing"); // the last chance to cancel
        if (m_shapefile)
            commitShapefile(m_temporaries, m_file, m_output, m_options.overwrite);
        else
            m_temporaries.commit(m_file, m_output);
        return {triangleCount()};
    }

    [[nodiscard]] std::uint64_t heldBytes() const override {
        const bool index = !m_shapefile && m_options.spatialIndex;
        return index ? triangleCount() * kFgbIndexBytesPerFeature : 0;
    }

private:
    fs::path m_output;
    TinWriteOptions m_options;
    bool m_shapefile;
    /// Declared before the dataset: destroyed after it is closed.
    AtomicOutput m_temporaries;
    std::optional<OGRSpatialReference> m_srs;
    /// Pieces report no progress: the tiles being built do.
    ProgressTicker m_pieceTicker;
    fs::path m_file;
    GDALDatasetUniquePtr m_dataset;
    OGRLayer* m_layer = nullptr;
    std::optional<TinMesh> m_held;
};

} // namespace

std::unique_ptr<TinStreamWriter> openOgrTinStream(const fs::path& output,
                                                  const TinWriteOptions& options) {
    if (options.format == TinFormat::Shapefile)
        checkShapefileName(output);
    return std::make_unique<OgrStreamWriter>(output, options);
}

} // namespace terratin::io::detail

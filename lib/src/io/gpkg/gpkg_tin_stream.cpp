#include "gpkg_tin_stream.hpp"

#include "../../stopwatch.hpp"
#include "../atomic_output.hpp"
#include "../ogr_dataset_support.hpp"
#include "../writer_support.hpp"
#include "gpkg_spatial_index.hpp"
#include "gpkg_tin_layers.hpp"
#include "gpkg_tin_writer.hpp"
#include "terratin/error.hpp"

#include <algorithm>
#include <optional>
#include <string>
#include <vector>

namespace terratin::io::detail {

namespace fs = std::filesystem;

namespace {

/// Pages sized as for a large table: a TIN cut in tiles is one.
constexpr std::uint64_t kLargeTin = std::uint64_t{1} << 20;

void widen(Extent2d& extent, const Extent2d& more, bool first) {
    if (first) {
        extent = more;
        return;
    }
    extent.minX = std::min(extent.minX, more.minX);
    extent.minY = std::min(extent.minY, more.minY);
    extent.maxX = std::max(extent.maxX, more.maxX);
    extent.maxY = std::max(extent.maxY, more.maxY);
}

/// One layer being filled: its table, its boxes for the index.
struct StreamedLayer {
    std::string name;
    std::optional<GpkgFeatureTable> table;
    std::vector<RtreeBox> boxes;
};

class GpkgStreamWriter final : public TinStreamWriter {
public:
    GpkgStreamWriter(fs::path output, const TinWriteOptions& options)
        : m_output(std::move(output)), m_options(options),
          m_temporaries(kOgrStage, m_output, existingTargetFor(options.overwrite)),
          m_temporary(m_temporaries.temporary(".gpkg")) {
        GpkgLayerNames names = gpkgLayerNames(options);
        names.nodeCells = options.nodes; // filled from the pieces' cells
        createGpkgTinLayers(m_temporary, kLargeTin, names, options, m_output);
        m_db.emplace(kOgrStage, m_temporary, m_output);
        configureForBulkWriting(*m_db);
        m_db->execute("BEGIN");
        m_triangles.name = names.triangles;
        m_triangles.table.emplace(*m_db, names.triangles);
        if (options.nodes) {
            m_nodes.name = names.nodes;
            m_nodes.table.emplace(*m_db, names.nodes);
        }
    }

    void append(const TinPiece& piece) override {
        const TinMesh& mesh = *piece.mesh;
        const auto firstTriangle = static_cast<std::int64_t>(triangleCount()) + 1;
        const auto firstVertex = static_cast<std::int64_t>(vertexCount()) + 1;
        TinMesh newVertices;
        std::vector<RasterCell> newCells;
        countPiece(piece, [&](std::size_t v) {
            newVertices.vertices.push_back(mesh.vertices[v]);
            if (!piece.cells.empty())
                newCells.push_back(piece.cells[v]);
        });
        if (mesh.triangleCount() > 0) {
            insertTriangleRows(*m_db, *m_triangles.table, mesh, m_options.attributes, firstTriangle,
                               [](std::uint64_t) {});
            keepBoxes(m_triangles, triangleBoxes(mesh));
        }
        if (newVertices.vertices.empty())
            return;
        widen(m_extent, meshExtent(newVertices), firstVertex == 1);
        if (m_nodes.table) {
            insertNodeRows(*m_db, *m_nodes.table, newVertices, newCells, firstVertex,
                           [](std::uint64_t) {});
            keepBoxes(m_nodes, nodeBoxes(newVertices));
        }
    }

    TinWriteResult finish(const ProgressCallback& progress) override {
        if (triangleCount() == 0)
            throw InvalidInputError(std::string(kOgrStage) +
                                    ": the mesh has no triangles; nothing written to " +
                                    quoted(m_output));
        std::vector<StreamedLayer*> layers{&m_triangles};
        if (m_nodes.table)
            layers.push_back(&m_nodes);
        m_triangles.table->finish(triangleCount(), m_extent);
        if (m_nodes.table)
            m_nodes.table->finish(vertexCount(), m_extent);
        std::uint64_t entries = 0;
        for (const StreamedLayer* layer : layers)
            entries += layer->boxes.size();
        const ProgressTicker ticker(kOgrStage, progress, m_output, 0.0, 0.98,
                                    m_options.spatialIndex ? entries : 0);
        TinWriteResult result;
        if (m_options.spatialIndex)
            result.indexSeconds = writeIndexes(layers, ticker);
        m_db->execute("COMMIT");
        m_db->close();
        ticker.report(entries, "Finishing GeoPackage"); // the last chance to cancel
        removeStaleJournals(m_output, m_options.overwrite);
        m_temporaries.commit(m_temporary, m_output);
        result.features = triangleCount() + (m_nodes.table ? vertexCount() : 0);
        return result;
    }

    [[nodiscard]] std::uint64_t heldBytes() const override {
        return (m_triangles.boxes.size() + m_nodes.boxes.size()) * sizeof(RtreeBox);
    }

private:
    void keepBoxes(StreamedLayer& layer, const std::vector<RtreeBox>& boxes) const {
        if (m_options.spatialIndex)
            layer.boxes.insert(layer.boxes.end(), boxes.begin(), boxes.end());
    }

    double writeIndexes(const std::vector<StreamedLayer*>& layers, const ProgressTicker& ticker) {
        const terratin::detail::Stopwatch time;
        const RtreeNodeSize nodeSize =
            RtreeNodeSize::forPage(static_cast<int>(m_db->queryInteger("PRAGMA page_size")));
        std::uint64_t done = 0;
        for (StreamedLayer* layer : layers) {
            const std::size_t count = layer->boxes.size();
            const PackedRtree tree(std::move(layer->boxes), nodeSize);
            writeGpkgSpatialIndex(*m_db, {layer->name, "geom", "fid"}, tree,
                                  [&](std::uint64_t stored) {
                                      ticker.report(done + stored, "Building spatial index");
                                  });
            done += count;
        }
        return time.seconds();
    }

    fs::path m_output;
    TinWriteOptions m_options;
    AtomicOutput m_temporaries;
    fs::path m_temporary;
    std::optional<SqliteConnection> m_db;
    StreamedLayer m_triangles;
    StreamedLayer m_nodes;
    Extent2d m_extent;
};

} // namespace

std::unique_ptr<TinStreamWriter> openGpkgTinStream(const fs::path& output,
                                                   const TinWriteOptions& options) {
    return std::make_unique<GpkgStreamWriter>(output, options);
}

} // namespace terratin::io::detail

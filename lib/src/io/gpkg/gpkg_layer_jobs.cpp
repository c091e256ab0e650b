#include "gpkg_layer_jobs.hpp"

#include "../../stopwatch.hpp"
#include "gpkg_spatial_index.hpp"
#include "gpkg_tin_writer.hpp"

#include <future>

namespace terratin::io::detail {

using terratin::detail::Stopwatch;

std::vector<GpkgLayerJob> gpkgLayerJobs(const TinMesh& mesh, const TinWriteOptions& options) {
    const GpkgLayerNames names = gpkgLayerNames(options);
    std::vector<GpkgLayerJob> jobs;
    jobs.push_back(
        {names.triangles, mesh.triangleCount(), "Writing triangles",
         [&](SqliteConnection& db, const GpkgFeatureTable& table, const RowProgress& progress) {
             insertTriangleRows(db, table, mesh, options.attributes, 1, progress);
         },
         [&] { return triangleBoxes(mesh); }});
    if (!names.nodes.empty())
        jobs.push_back(
            {names.nodes, mesh.vertexCount(), "Writing nodes",
             [&](SqliteConnection& db, const GpkgFeatureTable& table, const RowProgress& progress) {
                 insertNodeRows(db, table, mesh, options.vertexCells, 1, progress);
             },
             [&] { return nodeBoxes(mesh); }});
    if (!names.edges.empty())
        jobs.push_back(
            {names.edges, edgeCount(mesh), "Writing edges",
             [&](SqliteConnection& db, const GpkgFeatureTable& table, const RowProgress& progress) {
                 insertEdgeRows(db, table, mesh, options.constrainedEdges, progress);
             },
             [&] { return edgeBoxes(mesh); }});
    return jobs;
}

TinWriteResult fillGpkgLayers(SqliteConnection& db, const TinMesh& mesh,
                              const std::vector<GpkgLayerJob>& jobs, bool spatialIndex,
                              const ProgressTicker& ticker) {
    TinWriteResult result;
    const RtreeNodeSize nodeSize =
        RtreeNodeSize::forPage(static_cast<int>(db.queryInteger("PRAGMA main.page_size")));

    // The triangles' tree is packed on another thread while the rows go in.
    std::future<PackedRtree> firstTree;
    if (spatialIndex)
        firstTree = std::async(std::launch::async,
                               [&] { return PackedRtree(jobs.front().boxes(), nodeSize); });

    const Extent2d extent = meshExtent(mesh);
    const Stopwatch rowsTime;
    std::uint64_t done = 0;
    for (const auto& job : jobs) {
        GpkgFeatureTable table(db, job.name);
        job.rows(db, table,
                 [&](std::uint64_t rows) { ticker.report(done + rows, job.rowMessage); });
        table.finish(job.features, extent);
        done += job.features;
    }
    result.rowSeconds = rowsTime.seconds();

    const Stopwatch indexTime;
    for (std::size_t i = 0; spatialIndex && i < jobs.size(); ++i) {
        const PackedRtree tree = i == 0 ? firstTree.get() : PackedRtree(jobs[i].boxes(), nodeSize);
        writeGpkgSpatialIndex(db, {jobs[i].name, "geom", "fid"}, tree, [&](std::uint64_t entries) {
            ticker.report(done + entries, "Building spatial index");
        });
        done += jobs[i].features;
    }
    result.indexSeconds = indexTime.seconds();
    return result;
}

} // namespace terratin::io::detail

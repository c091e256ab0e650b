#include "terratin/triangulate/triangulate.hpp"

#include "dag_triangulator.hpp"
#include "insertion_order.hpp"

namespace terratin {

TriangulationResult triangulate(std::span<const Point3> points, const TriangulationOptions& options,
                                const ProgressCallback& progress) {
    const PreparedPoints prepared = preparePoints(points, options.duplicateZ);
    const auto count = static_cast<std::uint32_t>(prepared.local.size());

    detail::DagTriangulator triangulator(prepared.local);
    const std::vector<std::uint32_t> order =
        options.order == InsertionOrder::Brio
            ? detail::brioInsertionOrder(prepared.local, triangulator.highestVertex(), options.seed)
            : detail::randomInsertionOrder(count, triangulator.highestVertex(), options.seed);
    triangulator.insertAll(order, progress);

    TriangulationResult result;
    result.inputPoints = points.size();
    result.duplicatePoints = prepared.duplicateCount;
    result.historyNodes = triangulator.nodeCount();
    result.historyBytes = triangulator.memoryBytes();
    triangulator.extract(result.mesh.triangles, result.mesh.neighbours);

    // Vertices carry the caller's exact coordinates (not local + origin, to avoid relying on
    // the round trip) and the elevation chosen by the duplicate policy.
    result.mesh.sourceIndex = prepared.sourceIndex;
    result.mesh.vertices.reserve(count);
    for (std::uint32_t v = 0; v < count; ++v) {
        const Point3& source = points[prepared.sourceIndex[v]];
        result.mesh.vertices.push_back({source.x, source.y, prepared.z[v]});
    }
    if (progress)
        progress(1.0, "triangulated");
    return result;
}

} // namespace terratin

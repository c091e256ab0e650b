#include "polyline_insertion.hpp"

#include "terratin/error.hpp"

#include <optional>
#include <string>

namespace terratin::detail {

namespace {

std::string pointText(const Point3& p) {
    return "(" + std::to_string(p.x) + ", " + std::to_string(p.y) + ")";
}

// Point j's vertex: an existing one at its x and y, or a new one.
std::uint32_t pointVertex(ConstraintInserter& inserter, const ConstraintSet& constraints,
                          const std::vector<std::uint32_t>& vertices,
                          const std::vector<std::uint32_t>& start,
                          const PolylineProgress& progress) {
    const std::size_t k = progress.polyline;
    const std::size_t j = progress.nextPoint;
    const Point3& point = constraints.polylines[k][j];
    const bool given = !start.empty() || !constraints.polylineTriangles.empty();
    const std::uint32_t from = !start.empty() ? start[j]
                               : given        ? constraints.polylineTriangles[k][j]
                                              : kFromPreviousPoint;
    std::optional<std::uint32_t> v;
    if (!given || (from == kFromPreviousPoint && vertices.empty()))
        v = inserter.insertPoint(point, j == 0);
    else if (from == kFromPreviousPoint)
        v = inserter.insertPointFrom(point, inserter.mesh().halfEdgeLeaving(vertices.back()) / 3);
    else
        v = inserter.insertPointFrom(point, from);
    if (!v)
        throw InvalidInputError("insertConstraints: polyline " + std::to_string(k) + ", point " +
                                std::to_string(j) + " " + pointText(point) +
                                " lies outside the convex hull of the mesh (clipping is not "
                                "supported)");
    return *v;
}

} // namespace

void insertPolyline(ConstraintInserter& inserter, const ConstraintSet& constraints,
                    std::vector<std::uint32_t>& vertices, std::uint32_t firstOwner,
                    PolylineProgress& progress, const std::vector<std::uint32_t>& start) {
    const std::size_t points = constraints.polylines[progress.polyline].size();
    const auto insertSegments = [&] {
        if (!progress.pieces.empty()) {
            inserter.insertPieces(std::move(progress.pieces));
            progress.pieces.clear();
            ++progress.nextSegment;
        }
        for (; progress.nextSegment < vertices.size(); ++progress.nextSegment)
            inserter.insertSegment(
                vertices[progress.nextSegment - 1], vertices[progress.nextSegment],
                firstOwner + static_cast<std::uint32_t>(progress.nextSegment - 1));
    };
    try {
        for (; progress.nextPoint < points; ++progress.nextPoint)
            vertices.push_back(pointVertex(inserter, constraints, vertices, start, progress));
    } catch (const ZoneRefusal&) {
        // The segments between the points in so far go in now, while the mesh around them is
        // in cache, rather than with the rest of the polyline in the next round, cold. (A
        // refusal among them leaves its pieces, as any other.)
        insertSegments();
        throw;
    }
    insertSegments();
}

} // namespace terratin::detail

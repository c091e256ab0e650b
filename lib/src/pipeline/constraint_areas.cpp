#include "constraint_areas.hpp"

#include "terratin/error.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace terratin::detail {

namespace {

/// A triangle's region not visited yet (0: kept, 1: dropped).
constexpr std::uint8_t kUndecided = 2;

/// Whether a ray from `point` towards +x crosses `ring` an odd number of times.
bool oddCrossings(const std::vector<Point3>& ring, Point2 point) {
    bool odd = false;
    for (std::size_t i = 0, j = ring.size() - 1; i < ring.size(); j = i++)
        if ((ring[i].y > point.y) != (ring[j].y > point.y) &&
            point.x < (ring[j].x - ring[i].x) * (point.y - ring[i].y) / (ring[j].y - ring[i].y) +
                          ring[i].x)
            odd = !odd;
    return odd;
}

Point2 centroid(const TinMesh& mesh, std::size_t t) {
    Point2 sum{0.0, 0.0};
    for (std::size_t i = 0; i < 3; ++i) {
        sum.x += mesh.vertices[mesh.triangles[3 * t + i]].x / 3.0;
        sum.y += mesh.vertices[mesh.triangles[3 * t + i]].y / 3.0;
    }
    return sum;
}

/// Marks with `value` every triangle reached from `seed` without crossing a constrained edge.
void fillRegion(const ConstrainedTin& tin, std::size_t seed, std::uint8_t value,
                std::vector<std::uint8_t>& region, std::vector<std::size_t>& stack) {
    region[seed] = value;
    stack.assign(1, seed);
    while (!stack.empty()) {
        const std::size_t t = stack.back();
        stack.pop_back();
        for (std::size_t i = 0; i < 3; ++i) {
            const std::int32_t next = tin.mesh.neighbours[3 * t + i];
            if (next == kNoNeighbour || tin.constrained[3 * t + i] != 0)
                continue;
            const auto n = static_cast<std::size_t>(next);
            if (region[n] == kUndecided) {
                region[n] = value;
                stack.push_back(n);
            }
        }
    }
}

} // namespace

PolygonSet::PolygonSet(const io::LineLayer& rings) : m_rings(&rings) {
    for (std::size_t r = 0; r < rings.lines.size(); ++r) {
        if (r == 0 || rings.polygonOf[r] != rings.polygonOf[r - 1]) {
            m_firstRing.push_back(r);
            m_boxes.push_back({std::numeric_limits<double>::infinity(),
                               std::numeric_limits<double>::infinity(),
                               -std::numeric_limits<double>::infinity(),
                               -std::numeric_limits<double>::infinity()});
        }
        Box& box = m_boxes.back();
        for (const Point3& p : rings.lines[r]) {
            box.minX = std::min(box.minX, p.x);
            box.minY = std::min(box.minY, p.y);
            box.maxX = std::max(box.maxX, p.x);
            box.maxY = std::max(box.maxY, p.y);
        }
    }
    m_firstRing.push_back(rings.lines.size());
}

std::optional<std::size_t> PolygonSet::polygonHolding(Point2 point) const {
    for (std::size_t k = 0; k < m_boxes.size(); ++k) {
        const Box& box = m_boxes[k];
        if (point.x < box.minX || point.x > box.maxX || point.y < box.minY || point.y > box.maxY)
            continue;
        bool inside = false;
        for (std::size_t r = m_firstRing[k]; r < m_firstRing[k + 1]; ++r)
            inside = inside != oddCrossings(m_rings->lines[r], point);
        if (inside)
            return k;
    }
    return std::nullopt;
}

std::vector<std::uint8_t> regionsWhere(const ConstrainedTin& tin,
                                       const std::function<bool(Point2)>& inRegion) {
    std::vector<std::uint8_t> region(tin.mesh.triangleCount(), kUndecided);
    std::vector<std::size_t> stack;
    for (std::size_t t = 0; t < region.size(); ++t)
        if (region[t] == kUndecided)
            fillRegion(tin, t, inRegion(centroid(tin.mesh, t)) ? 1 : 0, region, stack);
    return region;
}

std::vector<std::uint8_t> trianglesOutsideArea(const ConstrainedTin& tin, const PolygonSet* clip,
                                               const PolygonSet* erase) {
    return regionsWhere(tin, [&](Point2 inner) {
        return (clip != nullptr && !clip->holds(inner)) ||
               (erase != nullptr && erase->holds(inner));
    });
}

std::vector<double> lowestLevelsOnBoundary(const PolygonSet& polygons, TinLocator& locator,
                                           double step) {
    const io::LineLayer& rings = polygons.layer();
    std::vector<double> lowest(polygons.polygonCount(), std::numeric_limits<double>::infinity());
    const auto sample = [&](std::size_t polygon, Point2 at) {
        if (const std::optional<double> z = locator.elevation(at))
            lowest[polygon] = std::min(lowest[polygon], *z);
    };
    std::size_t polygon = 0;
    for (std::size_t r = 0; r < rings.lines.size(); ++r) {
        if (r > 0 && rings.polygonOf[r] != rings.polygonOf[r - 1])
            ++polygon;
        const std::vector<Point3>& ring = rings.lines[r];
        for (std::size_t i = 0; i + 1 < ring.size(); ++i) {
            const Point3& a = ring[i];
            const Point3& b = ring[i + 1];
            const double length = std::hypot(b.x - a.x, b.y - a.y);
            const auto pieces = static_cast<std::size_t>(std::ceil(length / step));
            for (std::size_t s = 0; s < std::max<std::size_t>(pieces, 1); ++s) {
                const double f =
                    pieces == 0 ? 0.0 : static_cast<double>(s) / static_cast<double>(pieces);
                sample(polygon, {a.x + f * (b.x - a.x), a.y + f * (b.y - a.y)});
            }
        }
    }
    for (double& level : lowest)
        if (std::isinf(level))
            level = std::numeric_limits<double>::quiet_NaN();
    return lowest;
}

TinMesh flattenAreas(TinMesh mesh, const PolygonSet& areas, const std::vector<double>& levels,
                     const TriangulationOptions& options, std::size_t& removed) {
    std::vector<std::uint8_t> onHull(mesh.vertexCount(), 0);
    for (std::size_t e = 0; e < mesh.neighbours.size(); ++e)
        if (mesh.neighbours[e] == kNoNeighbour) {
            onHull[mesh.triangles[e]] = 1;
            onHull[mesh.triangles[e - e % 3 + (e + 1) % 3]] = 1;
        }
    // Hull vertices inside an area are flattened in place, the others marked to go.
    std::vector<std::uint8_t> leaves(mesh.vertexCount(), 0);
    for (std::size_t v = 0; v < mesh.vertexCount(); ++v) {
        Point3& p = mesh.vertices[v];
        if (const std::optional<std::size_t> area = areas.polygonHolding({p.x, p.y})) {
            if (onHull[v] != 0)
                p.z = levels[*area];
            else
                leaves[v] = 1;
        }
    }
    removed = static_cast<std::size_t>(std::count(leaves.begin(), leaves.end(), 1));
    if (removed == 0)
        return mesh;
    std::vector<Point3> kept;
    std::vector<std::uint32_t> keptSource;
    kept.reserve(mesh.vertexCount() - removed);
    keptSource.reserve(mesh.vertexCount() - removed);
    for (std::size_t v = 0; v < mesh.vertexCount(); ++v)
        if (leaves[v] == 0) {
            kept.push_back(mesh.vertices[v]);
            keptSource.push_back(mesh.sourceIndex[v]);
        }
    if (kept.size() < 3)
        throw InvalidInputError("Build: fewer than 3 input points lie outside the replace areas");
    mesh = {};
    TinMesh again = triangulate(kept, options).mesh;
    for (std::uint32_t& source : again.sourceIndex)
        source = keptSource[source];
    return again;
}

} // namespace terratin::detail

#include "constraint_areas.hpp"

#include "terratin/error.hpp"
#include "terratin/geometry/predicates.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <utility>

namespace terratin::detail {

namespace {

/// A triangle's region not visited yet (0: kept, 1: dropped).
constexpr std::uint8_t kUndecided = 2;

/// No half-edge, no triangle.
constexpr std::size_t kNone = std::numeric_limits<std::size_t>::max();

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

/// Whether `point` lies on a segment of `ring` (closed or not), exactly.
bool onPolyline(const std::vector<Point3>& ring, Point2 point) {
    for (std::size_t i = 1; i < ring.size(); ++i) {
        const Point2 a{ring[i - 1].x, ring[i - 1].y};
        const Point2 b{ring[i].x, ring[i].y};
        if (point.x < std::min(a.x, b.x) || point.x > std::max(a.x, b.x) ||
            point.y < std::min(a.y, b.y) || point.y > std::max(a.y, b.y))
            continue;
        if (predicates::orient2d(a, b, point) == 0.0)
            return true;
    }
    return false;
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

Point2 xyOf(const TinMesh& mesh, std::uint32_t v) {
    return {mesh.vertices[v].x, mesh.vertices[v].y};
}

/// The corner of triangle t that is vertex v.
std::size_t cornerOf(const TinMesh& mesh, std::size_t t, std::uint32_t v) {
    for (std::size_t k = 0; k < 3; ++k)
        if (mesh.triangles[3 * t + k] == v)
            return k;
    throw std::logic_error("Constraint areas: a vertex is not a corner of its triangle");
}

/// The triangles around vertex v, from triangle t (one of them): counter-clockwise (across the
/// edge into v), then, where the hull stops that turn, clockwise from t.
void trianglesAround(const TinMesh& mesh, std::uint32_t v, std::size_t t,
                     std::vector<std::size_t>& fan) {
    fan.assign(1, t);
    const std::size_t most = mesh.triangleCount(); // only a broken mesh has more
    for (std::size_t u = t;;) {
        const std::int32_t next = mesh.neighbours[3 * u + (cornerOf(mesh, u, v) + 2) % 3];
        if (next == kNoNeighbour)
            break;
        u = static_cast<std::size_t>(next);
        if (u == t)
            return; // all the way round
        fan.push_back(u);
        if (fan.size() > most)
            throw std::logic_error("Constraint areas: no end to the triangles round a vertex");
    }
    for (std::size_t u = t;;) {
        const std::int32_t next = mesh.neighbours[3 * u + cornerOf(mesh, u, v)];
        if (next == kNoNeighbour)
            return;
        u = static_cast<std::size_t>(next);
        fan.push_back(u);
        if (fan.size() > most)
            throw std::logic_error("Constraint areas: no end to the triangles round a vertex");
    }
}

/// For w exactly on the line through u and v (w != u): whether w lies on the ray from u
/// through v. Decided by comparisons alone, so exactly.
bool onRayFrom(Point2 u, Point2 v, Point2 w) {
    if (u.x != v.x)
        return (w.x > u.x) == (v.x > u.x) && w.x != u.x;
    return (w.y > u.y) == (v.y > u.y) && w.y != u.y;
}

/// The line of a walk out of the mesh, from a vertex towards a point outside it. Every side test
/// of the walk is orient2d's against this one line, so the triangles found hold the whole segment.
struct WalkLine {
    Point2 origin;
    Point2 towards;

    /// > 0 left of the line, < 0 right, 0 on it (orient2d, exact).
    [[nodiscard]] double side(const TinMesh& mesh, std::uint32_t w) const {
        return predicates::orient2d(origin, towards, xyOf(mesh, w));
    }
};

/// Counts a walk's steps, each past a vertex or through a triangle; the bound only guards a
/// broken mesh.
class WalkSteps {
public:
    explicit WalkSteps(const TinMesh& mesh) : m_most(2 * mesh.triangleCount() + 2) {}

    void step() {
        if (++m_steps > m_most)
            throw std::logic_error("Constraint areas: no end to a walk out of the mesh");
    }

private:
    std::size_t m_steps = 0;
    std::size_t m_most;
};

/// A vertex of the mesh on the walk's line, with a triangle round it.
struct VertexOnLine {
    std::uint32_t vertex;
    std::size_t triangle;
};

/// Where the segment goes on from a vertex on it: along an edge to the edge's other end
/// (`along`), into a triangle through the edge opposite the vertex (`exit`, that triangle's
/// half-edge), or neither: out of the mesh at the vertex.
struct PastVertex {
    std::size_t triangle = kNone;
    std::optional<std::uint32_t> along;
    std::size_t exit = kNone;
};

/// At `at` (on the line): the triangle whose angle at the vertex the segment enters (its corner
/// a right of the line, b left), or an edge the segment runs along, whose triangles on both
/// sides go to wall(t).
template <class Wall>
PastVertex leaveVertex(const TinMesh& mesh, const WalkLine& line, VertexOnLine at,
                       std::vector<std::size_t>& fan, Wall& wall) {
    const auto wallAcross = [&](std::size_t h) {
        if (mesh.neighbours[h] != kNoNeighbour)
            wall(static_cast<std::size_t>(mesh.neighbours[h]));
    };
    trianglesAround(mesh, at.vertex, at.triangle, fan);
    const Point2 pv = xyOf(mesh, at.vertex);
    for (const std::size_t u : fan) {
        const std::size_t k = cornerOf(mesh, u, at.vertex);
        const std::uint32_t a = mesh.triangles[3 * u + (k + 1) % 3];
        const std::uint32_t b = mesh.triangles[3 * u + (k + 2) % 3];
        const double sideA = line.side(mesh, a);
        const double sideB = line.side(mesh, b);
        if (sideA == 0.0 && onRayFrom(pv, line.towards, xyOf(mesh, a))) {
            wall(u);
            wallAcross(3 * u + k);
            return {u, a, kNone};
        }
        if (sideB == 0.0 && onRayFrom(pv, line.towards, xyOf(mesh, b))) {
            wall(u);
            wallAcross(3 * u + (k + 2) % 3);
            return {u, b, kNone};
        }
        if (sideA < 0.0 && sideB > 0.0) {
            wall(u);
            return {u, std::nullopt, 3 * u + (k + 1) % 3};
        }
    }
    return {};
}

/// Through triangles from half-edge `exit`, each entered by an edge from its vertex right of the
/// line to the one left of it, every one to wall(t), until the segment reaches a vertex (returned,
/// with the triangle it was reached in) or leaves the mesh (nullopt).
template <class Wall>
std::optional<VertexOnLine> crossTriangles(const TinMesh& mesh, const WalkLine& line,
                                           std::size_t exit, WalkSteps& steps, Wall& wall) {
    for (;;) {
        steps.step();
        if (mesh.neighbours[exit] == kNoNeighbour)
            return std::nullopt;
        const std::uint32_t left = mesh.triangles[exit - exit % 3 + (exit % 3 + 1) % 3];
        const auto u = static_cast<std::size_t>(mesh.neighbours[exit]);
        wall(u);
        const std::size_t k = cornerOf(mesh, u, left); // u is (left, right, w)
        const std::uint32_t w = mesh.triangles[3 * u + (k + 2) % 3];
        const double sideW = line.side(mesh, w);
        if (sideW == 0.0)
            return VertexOnLine{w, u};
        exit = sideW > 0.0 ? 3 * u + (k + 1) % 3  // right -> w
                           : 3 * u + (k + 2) % 3; // w -> left
    }
}

/// Calls wall(t) for every triangle that the segment from vertex `from` (a corner of triangle
/// `start`) towards `towards` (outside the mesh) passes through before it leaves the mesh, and for
/// the triangles on both sides of an edge it runs along (WalkLine: the triangles found hold the
/// whole segment inside the mesh).
template <class Wall>
void trianglesOnTheWayOut(const TinMesh& mesh, std::uint32_t from, std::size_t start,
                          Point2 towards, Wall&& wall) {
    const WalkLine line{xyOf(mesh, from), towards};
    WalkSteps steps(mesh);
    std::vector<std::size_t> fan;
    VertexOnLine at{from, start};
    for (;;) {
        steps.step();
        const PastVertex past = leaveVertex(mesh, line, at, fan, wall);
        if (past.along) {
            at = {*past.along, past.triangle};
            continue;
        }
        if (past.exit == kNone)
            return; // the segment leaves the mesh at the vertex
        const std::optional<VertexOnLine> reached =
            crossTriangles(mesh, line, past.exit, steps, wall);
        if (!reached)
            return;
        at = *reached;
    }
}

/// Decides on its own, by its centroid, every triangle on the way out of the hull from each of
/// `openEnds` (trianglesOnTheWayOut): no region is filled through them.
void decideOpenEnds(const ConstrainedTin& tin, std::span<const OpenRingEnd> openEnds,
                    const std::function<bool(Point2)>& inRegion,
                    std::vector<std::uint8_t>& region) {
    const TinMesh& mesh = tin.mesh;
    // The ends' vertices, sorted, each with a triangle of its found in one pass.
    std::vector<std::pair<std::uint32_t, std::size_t>> ends;
    for (std::size_t i = 0; i < openEnds.size(); ++i) {
        const std::vector<std::uint32_t>& chain = tin.chains.at(openEnds[i].chain);
        if (!chain.empty())
            ends.emplace_back(openEnds[i].atLast ? chain.back() : chain.front(), i);
    }
    if (ends.empty())
        return;
    std::sort(ends.begin(), ends.end());
    std::vector<std::size_t> triangleOf(ends.size(), kNone);
    std::size_t found = 0;
    for (std::size_t t = 0; t < mesh.triangleCount() && found < ends.size(); ++t)
        for (std::size_t k = 0; k < 3; ++k) {
            const std::uint32_t c = mesh.triangles[3 * t + k];
            if (c < ends.front().first || c > ends.back().first)
                continue;
            for (auto e = std::lower_bound(ends.begin(), ends.end(), std::pair{c, std::size_t{0}});
                 e != ends.end() && e->first == c; ++e) {
                std::size_t& slot = triangleOf[static_cast<std::size_t>(e - ends.begin())];
                if (slot == kNone) {
                    slot = t;
                    ++found;
                }
            }
        }
    for (std::size_t e = 0; e < ends.size(); ++e) {
        if (triangleOf[e] == kNone)
            throw std::logic_error("Constraint areas: a ring's end is in no triangle");
        trianglesOnTheWayOut(mesh, ends[e].first, triangleOf[e], openEnds[ends[e].second].outside,
                             [&](std::size_t t) {
                                 if (region[t] == kUndecided)
                                     region[t] = inRegion(centroid(mesh, t)) ? 1 : 0;
                             });
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

bool PolygonSet::onRing(Point2 point) const {
    for (std::size_t k = 0; k < m_boxes.size(); ++k) {
        const Box& box = m_boxes[k];
        if (point.x < box.minX || point.x > box.maxX || point.y < box.minY || point.y > box.maxY)
            continue;
        for (std::size_t r = m_firstRing[k]; r < m_firstRing[k + 1]; ++r)
            if (onPolyline(m_rings->lines[r], point))
                return true;
    }
    return false;
}

std::vector<std::uint8_t> regionsWhere(const ConstrainedTin& tin,
                                       std::span<const OpenRingEnd> openEnds,
                                       const std::function<bool(Point2)>& inRegion) {
    std::vector<std::uint8_t> region(tin.mesh.triangleCount(), kUndecided);
    decideOpenEnds(tin, openEnds, inRegion, region);
    std::vector<std::size_t> stack;
    for (std::size_t t = 0; t < region.size(); ++t)
        if (region[t] == kUndecided)
            fillRegion(tin, t, inRegion(centroid(tin.mesh, t)) ? 1 : 0, region, stack);
    return region;
}

std::vector<std::uint8_t> trianglesOutsideArea(const ConstrainedTin& tin,
                                               std::span<const OpenRingEnd> openEnds,
                                               const PolygonSet* clip, const PolygonSet* erase) {
    return regionsWhere(tin, openEnds, [&](Point2 inner) {
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

#include "hull_interior.hpp"

#include "terratin/geometry/predicates.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <unordered_map>
#include <utility>

namespace terratin::detail {

namespace {

Point2 planar(const Point3& p) {
    return {p.x, p.y};
}

// The hull edges' cycle of vertices, from the first edge on; nullopt unless the edges form
// exactly one cycle.
std::optional<std::vector<std::uint32_t>>
hullCycle(const std::vector<std::array<std::uint32_t, 2>>& edges) {
    std::unordered_map<std::uint32_t, std::uint32_t> next;
    next.reserve(edges.size());
    for (const auto& [from, to] : edges)
        if (!next.emplace(from, to).second)
            return std::nullopt; // two edges leave one vertex
    std::vector<std::uint32_t> cycle;
    std::uint32_t v = edges.front()[0];
    do {
        cycle.push_back(v);
        const auto found = next.find(v);
        if (found == next.end() || cycle.size() > edges.size())
            return std::nullopt;
        v = found->second;
    } while (v != edges.front()[0]);
    if (cycle.size() != edges.size())
        return std::nullopt; // more than one cycle: triangles left out
    return cycle;
}

// The hull as a strictly convex polygon, counter-clockwise, its corners alone (the vertices
// where it runs straight on dropped); nullopt unless every turn is to the left or straight on
// and the corners go once round the first.
std::optional<std::vector<Point2>>
convexPolygon(const MeshArray<Point3>& vertices,
              const std::vector<std::array<std::uint32_t, 2>>& edges) {
    if (edges.size() < 3)
        return std::nullopt;
    const std::optional<std::vector<std::uint32_t>> cycle = hullCycle(edges);
    if (!cycle)
        return std::nullopt;
    const std::size_t n = cycle->size();
    std::vector<Point2> corners;
    for (std::size_t i = 0; i < n; ++i) {
        const Point2 a = planar(vertices[(*cycle)[(i + n - 1) % n]]);
        const Point2 b = planar(vertices[(*cycle)[i]]);
        const Point2 c = planar(vertices[(*cycle)[(i + 1) % n]]);
        const double turn = predicates::orient2d(a, b, c);
        if (turn < 0.0)
            return std::nullopt;
        if (turn > 0.0)
            corners.push_back(b);
        else if ((b.x - a.x) * (c.x - b.x) + (b.y - a.y) * (c.y - b.y) <= 0.0)
            return std::nullopt; // turning back on itself
    }
    const std::size_t m = corners.size();
    if (m < 3 || predicates::orient2d(corners[0], corners[1], corners[m - 1]) <= 0.0)
        return std::nullopt;
    for (std::size_t i = 1; i + 1 < m; ++i)
        if (predicates::orient2d(corners[0], corners[i], corners[i + 1]) <= 0.0)
            return std::nullopt;
    return corners;
}

// Whether `q` lies inside the strictly convex counter-clockwise `polygon` or on it, exactly:
// a binary search for the wedge from the first corner that holds q, then the side of that
// wedge's edge. O(log corners).
bool insideOrOn(const std::vector<Point2>& polygon, Point2 q) {
    const Point2 first = polygon.front();
    if (predicates::orient2d(first, polygon[1], q) < 0.0 ||
        predicates::orient2d(first, polygon.back(), q) > 0.0)
        return false;
    std::size_t low = 1;
    std::size_t high = polygon.size() - 1;
    while (high - low > 1) {
        const std::size_t middle = (low + high) / 2;
        if (predicates::orient2d(first, polygon[middle], q) >= 0.0)
            low = middle;
        else
            high = middle;
    }
    return predicates::orient2d(polygon[low], polygon[low + 1], q) >= 0.0;
}

// The x range of the polygon's section at height y, in double; low > high where the line
// misses it.
std::pair<double, double> sectionAt(const std::vector<Point2>& polygon, double y) {
    double low = std::numeric_limits<double>::infinity();
    double high = -low;
    for (std::size_t i = 0; i < polygon.size(); ++i) {
        const Point2 a = polygon[i];
        const Point2 b = polygon[(i + 1) % polygon.size()];
        if (y < std::min(a.y, b.y) || y > std::max(a.y, b.y))
            continue;
        const double x0 =
            a.y == b.y ? std::min(a.x, b.x) : a.x + (y - a.y) / (b.y - a.y) * (b.x - a.x);
        const double x1 = a.y == b.y ? std::max(a.x, b.x) : x0;
        low = std::min(low, x0);
        high = std::max(high, x1);
    }
    return {low, high};
}

} // namespace

HullInterior::HullInterior(const MeshArray<Point3>& vertices,
                           const std::vector<std::array<std::uint32_t, 2>>& hullEdges,
                           Point2 origin, double rowHeight, std::size_t rows)
    : m_origin(origin), m_rowHeight(rowHeight) {
    const std::optional<std::vector<Point2>> polygon = convexPolygon(vertices, hullEdges);
    if (!polygon)
        return;
    double bottom = polygon->front().y;
    double top = bottom;
    for (const Point2 corner : *polygon) {
        bottom = std::min(bottom, corner.y);
        top = std::max(top, corner.y);
    }
    const Box empty{{1.0, 1.0}, {0.0, 0.0}};
    m_rows.assign(rows, empty);
    for (std::size_t r = 0; r < rows; ++r) {
        const double y0 = std::max(bottom, origin.y + static_cast<double>(r) * rowHeight);
        const double y1 = std::min(top, origin.y + static_cast<double>(r + 1) * rowHeight);
        if (!(y0 <= y1))
            continue;
        // The hull is convex, so the box between the two sections' common x range lies in
        // it; the range is computed in double, so each box is shrunk until its corners pass
        // the exact test (a few ulps; a row whose box never does is left empty).
        const auto [low0, high0] = sectionAt(*polygon, y0);
        const auto [low1, high1] = sectionAt(*polygon, y1);
        const double low = std::max(low0, low1);
        const double high = std::min(high0, high1);
        for (const double shrink : {1e-12, 1e-9, 1e-6}) {
            const double margin = shrink * (high - low);
            const Box box{{low + margin, y0}, {high - margin, y1}};
            if (!(box.low.x <= box.high.x))
                break;
            if (insideOrOn(*polygon, box.low) && insideOrOn(*polygon, box.high) &&
                insideOrOn(*polygon, {box.low.x, box.high.y}) &&
                insideOrOn(*polygon, {box.high.x, box.low.y})) {
                m_rows[r] = box;
                break;
            }
        }
    }
}

bool HullInterior::holds(Point2 point) const {
    const double row = (point.y - m_origin.y) / m_rowHeight;
    if (!(row >= 0.0 && row < static_cast<double>(m_rows.size())))
        return false;
    const Box& box = m_rows[static_cast<std::size_t>(row)];
    return box.low.x <= point.x && point.x <= box.high.x && box.low.y <= point.y &&
           point.y <= box.high.y;
}

} // namespace terratin::detail

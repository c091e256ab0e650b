#pragma once
/// @file
/// The polygons of --clip, --erase and --replace as areas: which polygon holds a point, which
/// triangles of a constrained TIN lie in them, and the flat level of each replace polygon.

#include "terratin/constrain/constrained_tin.hpp"
#include "terratin/geometry/point.hpp"
#include "terratin/io/ogr_line_reader.hpp"
#include "terratin/triangulate/tin_locator.hpp"
#include "terratin/triangulate/triangulate.hpp"

#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <vector>

namespace terratin::detail {

/// The polygons of a polygon layer (io::readOgrPolygons), for point-in-polygon queries: each
/// polygon's rings and bounding box, so that a query tests only the polygons whose box holds
/// the point. Holds a pointer to the layer, which must outlive it.
class PolygonSet {
public:
    explicit PolygonSet(const io::LineLayer& rings);

    /// The first polygon, in layer order, whose inside holds `point` (even-odd over its rings:
    /// a hole's inside is outside); nullopt for none. A point on a ring may count either way.
    [[nodiscard]] std::optional<std::size_t> polygonHolding(Point2 point) const;
    [[nodiscard]] bool holds(Point2 point) const { return polygonHolding(point).has_value(); }
    /// Whether `point` lies exactly on a ring of a polygon (orient2d, exact).
    [[nodiscard]] bool onRing(Point2 point) const;

    [[nodiscard]] std::size_t polygonCount() const { return m_boxes.size(); }
    [[nodiscard]] const io::LineLayer& layer() const { return *m_rings; }

private:
    struct Box {
        double minX, minY, maxX, maxY;
    };
    const io::LineLayer* m_rings;
    /// Polygon k's rings are m_firstRing[k] to m_firstRing[k + 1] - 1.
    std::vector<std::size_t> m_firstRing;
    std::vector<Box> m_boxes;
};

/// Where an area's ring, clipped to the convex hull (TinLocator::clipToSurface), stops short of
/// it: the first vertex of chain `chain` of the TIN (its last with `atLast`) is a cut point, and
/// the ring's segment went on from there to `outside`, a point outside the hull.
struct OpenRingEnd {
    std::size_t chain = 0;
    bool atLast = false;
    Point2 outside{};
};

/// 1 for every triangle of `tin` in a region that `inRegion` accepts at one of its triangles'
/// centroid, else 0. A region is a set of triangles joined across unconstrained edges; the
/// areas' rings are constrained chains, so no region straddles one, and each region is decided
/// once. A ring cut at the hull ends a few ulps inside it, and a region would reach round that
/// end: so the triangles that the rest of its segment passes through on its way out of the hull
/// (from each of `openEnds`, exactly by orient2d, with those on both sides of an edge it runs
/// along) are decided one by one, and no region reaches through them. O(triangles) plus one call
/// per region, and per open end a walk as long as the rest of its segment.
std::vector<std::uint8_t> regionsWhere(const ConstrainedTin& tin,
                                       std::span<const OpenRingEnd> openEnds,
                                       const std::function<bool(Point2)>& inRegion);

/// 1 for every triangle of `tin` outside `clip` (when given) or inside `erase` (when given)
/// (regionsWhere).
std::vector<std::uint8_t> trianglesOutsideArea(const ConstrainedTin& tin,
                                               std::span<const OpenRingEnd> openEnds,
                                               const PolygonSet* clip, const PolygonSet* erase);

/// Each replace polygon's flat level: the lowest elevation of `locator`'s surface on the
/// polygon's rings, sampled at every ring point and every `step` along each segment (only where
/// the surface is, inside its hull); NaN for a polygon whose rings all lie outside the hull.
std::vector<double> lowestLevelsOnBoundary(const PolygonSet& polygons, TinLocator& locator,
                                           double step);

/// `mesh` without the vertices inside any polygon of `areas`, triangulated again with
/// `options` (sourceIndex still indexes the caller's input points). Vertices on the convex hull
/// stay, at their polygon's level in `levels`, so that the TIN still covers the data. Sets
/// `removed` to the number of vertices left out; returns `mesh` unchanged when there are none.
/// Throws InvalidInputError when fewer than 3 vertices are left.
TinMesh flattenAreas(TinMesh mesh, const PolygonSet& areas, const std::vector<double>& levels,
                     const TriangulationOptions& options, std::size_t& removed);

} // namespace terratin::detail

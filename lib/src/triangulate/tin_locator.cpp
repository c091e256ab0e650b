#include "terratin/triangulate/tin_locator.hpp"

#include "../parallel/parallel_for.hpp"
#include "hull_interior.hpp"
#include "terratin/geometry/predicates.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <memory>
#include <optional>

namespace terratin {

namespace {

Point2 planar(const Point3& p) {
    return {p.x, p.y};
}

// `triangle`'s corners from the one with the lowest index on, in their order.
std::array<std::uint32_t, 3> cornersFromLowest(const TinMesh& mesh, std::uint32_t triangle) {
    const std::uint32_t* stored = &mesh.triangles[3 * std::size_t{triangle}];
    const std::size_t first =
        stored[1] < stored[0] ? (stored[2] < stored[1] ? 2 : 1) : (stored[2] < stored[0] ? 2 : 0);
    return {stored[first], stored[(first + 1) % 3], stored[(first + 2) % 3]};
}

// The z at `point` along the edge between vertices a and b, interpolated from the one with the
// lower index, when the point lies exactly on the edge's line.
std::optional<double> elevationOnEdge(const TinMesh& mesh, std::uint32_t a, std::uint32_t b,
                                      Point2 point) {
    const Point3& u = mesh.vertices[std::min(a, b)];
    const Point3& v = mesh.vertices[std::max(a, b)];
    if (predicates::orient2d(planar(u), planar(v), point) != 0.0)
        return std::nullopt;
    const double dx = v.x - u.x;
    const double dy = v.y - u.y;
    const double t = ((point.x - u.x) * dx + (point.y - u.y) * dy) / (dx * dx + dy * dy);
    return u.z + t * (v.z - u.z);
}

// The half-edge after h in its triangle.
std::size_t nextInTriangle(std::size_t h) {
    return h - h % 3 + (h % 3 + 1) % 3;
}

// Where a walk ended: in `triangle`, or leaving the mesh by the hull half-edge `exit`; neither
// when it did not end (a broken mesh).
struct WalkEnd {
    std::optional<std::uint32_t> triangle;
    std::optional<std::size_t> exit;
};

// Whether `point` lies strictly right of a -> b, by the exact test.
bool orient2dRight(Point2 a, Point2 b, Point2 point) {
    return predicates::orient2d(a, b, point) < 0.0;
}

// A remembering stochastic walk (Devillers, Pion & Teillaud) from triangle t towards `point`,
// `outside(a, b, p)` saying p lies beyond edge a-b: it never goes back through the edge it came
// in by and tries the other two in a random order (`random`, a generator's state), so it ends
// on any triangulation, constrained ones included, where a fixed order may cycle. The bound
// only guards a broken mesh.
template <class OutsideOf>
WalkEnd walkTowards(const TinMesh& mesh, std::uint32_t t, Point2 point, OutsideOf outside,
                    std::uint64_t& random) {
    const std::size_t triangles = mesh.triangleCount();
    std::int32_t previous = kNoNeighbour;
    for (std::size_t step = 0; step < 16 * triangles + 16; ++step) {
        random = random * 6364136223846793005ULL + 1442695040888963407ULL;
        const auto first = static_cast<std::size_t>((random >> 33U) % 3U);
        int exitEdge = -1;
        for (std::size_t k = 0; k < 3 && exitEdge < 0; ++k) {
            const std::size_t i = (k + first) % 3;
            if (previous != kNoNeighbour && mesh.neighbours[3 * t + i] == previous)
                continue;
            const Point2 a = planar(mesh.vertices[mesh.triangles[3 * t + i]]);
            const Point2 b = planar(mesh.vertices[mesh.triangles[3 * t + (i + 1) % 3]]);
            if (outside(a, b, point))
                exitEdge = static_cast<int>(i);
        }
        if (exitEdge < 0)
            return {t, std::nullopt};
        const std::size_t exit = 3 * std::size_t{t} + static_cast<std::size_t>(exitEdge);
        // Strictly outside a hull edge: outside the convex hull.
        if (mesh.neighbours[exit] == kNoNeighbour)
            return {std::nullopt, exit};
        previous = static_cast<std::int32_t>(t);
        t = static_cast<std::uint32_t>(mesh.neighbours[exit]);
    }
    return {};
}

// The half-edges as vertex pairs, in triangle order.
std::vector<std::array<std::uint32_t, 2>> edgesInTriangleOrder(const TinMesh& mesh,
                                                               std::vector<std::size_t> halfEdges) {
    std::sort(halfEdges.begin(), halfEdges.end());
    std::vector<std::array<std::uint32_t, 2>> edges;
    edges.reserve(halfEdges.size());
    for (const std::size_t h : halfEdges)
        edges.push_back({mesh.triangles[h], mesh.triangles[nextInTriangle(h)]});
    return edges;
}

// The mesh's edges with no neighbour, in triangle order: a pass over every triangle.
std::vector<std::array<std::uint32_t, 2>> hullEdgesOf(const TinMesh& mesh, unsigned threads) {
    const std::size_t count = mesh.triangleCount();
    std::vector<std::vector<std::size_t>> perBlock(detail::parallelForThreads(count, threads));
    detail::parallelFor(count, threads, [&](unsigned block, std::size_t begin, std::size_t end) {
        for (std::size_t h = 3 * begin; h < 3 * end; ++h)
            if (mesh.neighbours[h] == kNoNeighbour)
                perBlock[block].push_back(h);
    });
    std::vector<std::size_t> halfEdges;
    for (const std::vector<std::size_t>& block : perBlock)
        halfEdges.insert(halfEdges.end(), block.begin(), block.end());
    return edgesInTriangleOrder(mesh, std::move(halfEdges));
}

// A half-edge of the hull of a mesh that covers its convex hull: the one a walk from triangle
// 0 towards a point far to the left of vertex 0 leaves the mesh by. Nothing when that point was
// not far enough to lie outside (a mesh wider than a million times its coordinates).
std::optional<std::size_t> hullHalfEdgeFromWalk(const TinMesh& mesh) {
    const Point3& corner = mesh.vertices[mesh.triangles[0]];
    const Point2 far{corner.x - 1e6 * (1.0 + std::fabs(corner.x) + std::fabs(corner.y)), corner.y};
    std::uint64_t random = 1; // any state: the walk ends from any
    return walkTowards(mesh, 0, far, orient2dRight, random).exit;
}

// The hull edges of a mesh that covers its convex hull, found from `first` (one of them) by
// turning round each hull vertex to the next hull edge: O(hull vertices x degree). In triangle
// order, as hullEdgesOf gives them. Nothing when the turns do not come back to `first` (a mesh
// whose links are broken).
std::optional<std::vector<std::array<std::uint32_t, 2>>> hullEdgesAround(const TinMesh& mesh,
                                                                         std::size_t first) {
    std::vector<std::size_t> halfEdges;
    std::size_t h = first;
    for (std::size_t turns = 0; turns <= mesh.triangles.size(); ++turns) {
        if (mesh.neighbours[h] == kNoNeighbour) {
            if (!halfEdges.empty() && h == first)
                return edgesInTriangleOrder(mesh, std::move(halfEdges));
            halfEdges.push_back(h);
            h = nextInTriangle(h); // leaves the hull edge's end
            continue;
        }
        // Across h, into the triangle that holds it reversed: its half-edge leaving the same
        // vertex is one turn further round it.
        const std::uint32_t vertex = mesh.triangles[h];
        const std::size_t base = 3 * static_cast<std::size_t>(mesh.neighbours[h]);
        std::size_t i = 0;
        while (i < 3 && mesh.triangles[base + i] != vertex)
            ++i;
        if (i == 3)
            return std::nullopt;
        h = base + i;
    }
    return std::nullopt;
}

// The vertices' bounding box, as (low, high). Precondition: at least one vertex.
std::array<Point2, 2> boundsOf(const MeshArray<Point3>& vertices, unsigned threads) {
    const Point2 first{vertices[0].x, vertices[0].y};
    std::vector<std::array<Point2, 2>> perBlock(
        detail::parallelForThreads(vertices.size(), threads), {first, first});
    detail::parallelFor(
        vertices.size(), threads, [&](unsigned block, std::size_t begin, std::size_t end) {
            auto& [low, high] = perBlock[block];
            for (std::size_t v = begin; v < end; ++v) {
                low = {std::min(low.x, vertices[v].x), std::min(low.y, vertices[v].y)};
                high = {std::max(high.x, vertices[v].x), std::max(high.y, vertices[v].y)};
            }
        });
    std::array<Point2, 2> bounds{first, first};
    for (const auto& [low, high] : perBlock)
        bounds = {Point2{std::min(bounds[0].x, low.x), std::min(bounds[0].y, low.y)},
                  Point2{std::max(bounds[1].x, high.x), std::max(bounds[1].y, high.y)}};
    return bounds;
}

// The bounding box of the hull edges' vertices, as (low, high): every vertex's for a mesh that
// covers its convex hull, at the cost of the hull alone (where triangles were left out, the box
// of those kept, which holds all their corners: the buckets need no more). Precondition:
// `edges` not empty.
std::array<Point2, 2> boundsOfHull(const TinMesh& mesh,
                                   const std::vector<std::array<std::uint32_t, 2>>& edges) {
    const Point3& first = mesh.vertices[edges.front()[0]];
    Point2 low{first.x, first.y};
    Point2 high = low;
    for (const auto& edge : edges) {
        const Point3& p = mesh.vertices[edge[0]];
        low = {std::min(low.x, p.x), std::min(low.y, p.y)};
        high = {std::max(high.x, p.x), std::max(high.y, p.y)};
    }
    return {low, high};
}

} // namespace

TinLocator::TinLocator(const TinMesh& mesh, unsigned threads) : TinLocator(mesh, Use{threads}) {}

TinLocator::TinLocator(const TinMesh& mesh, const Use& use) : m_mesh(&mesh) {
    const unsigned threads = detail::threadsOrAll(use.threads);
    std::optional<std::vector<std::array<std::uint32_t, 2>>> hull;
    if (use.coversConvexHull && mesh.triangleCount() > 0)
        if (const std::optional<std::size_t> first = hullHalfEdgeFromWalk(mesh))
            hull = hullEdgesAround(mesh, *first);
    m_hullEdges = std::make_shared<const std::vector<std::array<std::uint32_t, 2>>>(
        hull ? std::move(*hull) : hullEdgesOf(mesh, threads));
    if (mesh.vertexCount() == 0)
        return;
    const auto [low, high] =
        m_hullEdges->empty() ? boundsOf(mesh.vertices, threads) : boundsOfHull(mesh, *m_hullEdges);
    // About kTrianglesPerBucket triangles per bucket, where every triangle may be asked for: a
    // walk from a bucket's triangle to any point of the bucket crosses a few of them. For a
    // few far queries, a few buckets each.
    constexpr double kTrianglesPerBucket = 16.0;
    constexpr double kBucketsPerFarQuery = 4.0;
    constexpr double kFewestBuckets = 256.0;
    const double area = (high.x - low.x) * (high.y - low.y);
    const double triangles = static_cast<double>(mesh.triangleCount());
    double bucketCount = std::max(1.0, triangles / kTrianglesPerBucket);
    if (use.farQueries > 0)
        bucketCount = std::min(
            bucketCount,
            std::max(kFewestBuckets, kBucketsPerFarQuery * static_cast<double>(use.farQueries)));
    m_bucketSize = area > 0.0 ? std::sqrt(area / bucketCount)
                              : std::max({high.x - low.x, high.y - low.y, 1.0});
    m_origin = low;
    m_columns = static_cast<std::size_t>((high.x - low.x) / m_bucketSize) + 1;
    m_rows = static_cast<std::size_t>((high.y - low.y) / m_bucketSize) + 1;
    m_hullHigh = high;
    // About 4 triangles looked at per bucket still leave few buckets empty, and a walk from
    // any triangle of a bucket is as short; the corners read at random are the fill's cost.
    constexpr double kSamplesPerBucket = 4.0;
    const auto stride =
        static_cast<std::size_t>(std::max(1.0, triangles / (kSamplesPerBucket * bucketCount)));
    std::vector<std::uint32_t> buckets = fillBuckets(stride, threads);
    fillEmptyBuckets(buckets);
    m_buckets = std::make_shared<const std::vector<std::uint32_t>>(std::move(buckets));
    m_interior = std::make_shared<const detail::HullInterior>(mesh.vertices, *m_hullEdges, m_origin,
                                                              m_bucketSize, m_rows);
}

// Each bucket gets the first triangle, in index order, whose first corner lies in it, of every
// `stride`-th triangle: each thread fills a grid from its own range of triangles, and the
// lowest range's wins.
std::vector<std::uint32_t> TinLocator::fillBuckets(std::size_t stride, unsigned threads) const {
    const TinMesh& mesh = *m_mesh;
    const std::size_t count = mesh.triangleCount();
    std::vector<std::vector<std::uint32_t>> perBlock(detail::parallelForThreads(count, threads));
    detail::parallelFor(count, threads, [&](unsigned block, std::size_t begin, std::size_t end) {
        std::vector<std::uint32_t>& grid = perBlock[block];
        grid.assign(m_columns * m_rows, kNoTriangle);
        for (std::size_t t = (begin + stride - 1) / stride * stride; t < end; t += stride) {
            const Point3& corner = mesh.vertices[mesh.triangles[3 * t]];
            const auto column = std::min(
                static_cast<std::size_t>((corner.x - m_origin.x) / m_bucketSize), m_columns - 1);
            const auto row = std::min(
                static_cast<std::size_t>((corner.y - m_origin.y) / m_bucketSize), m_rows - 1);
            std::uint32_t& bucket = grid[row * m_columns + column];
            if (bucket == kNoTriangle)
                bucket = static_cast<std::uint32_t>(t);
        }
    });
    std::vector<std::uint32_t> buckets = std::move(perBlock.front());
    for (std::size_t block = 1; block < perBlock.size(); ++block)
        for (std::size_t b = 0; b < buckets.size(); ++b)
            if (buckets[b] == kNoTriangle)
                buckets[b] = perBlock[block][b];
    return buckets;
}

void TinLocator::fillEmptyBuckets(std::vector<std::uint32_t>& buckets) const {
    // Along each row and then each column, both ways, an empty bucket takes its filled
    // neighbour's triangle: a walk from a bucket outside the hull or inside a large triangle
    // starts a few buckets away, not wherever the last query ended.
    const auto fillLine = [&](std::size_t first, std::size_t count, std::size_t stride) {
        for (std::size_t k = 1; k < count; ++k) {
            std::uint32_t& bucket = buckets[first + k * stride];
            if (bucket == kNoTriangle)
                bucket = buckets[first + (k - 1) * stride];
        }
        for (std::size_t k = count - 1; k-- > 0;) {
            std::uint32_t& bucket = buckets[first + k * stride];
            if (bucket == kNoTriangle)
                bucket = buckets[first + (k + 1) * stride];
        }
    };
    for (std::size_t row = 0; row < m_rows; ++row)
        fillLine(row * m_columns, m_columns, 1);
    for (std::size_t column = 0; column < m_columns; ++column)
        fillLine(column, m_rows, m_columns);
}

std::uint32_t TinLocator::startNear(Point2 point) const {
    if (!m_buckets || m_buckets->empty())
        return m_last;
    const double column =
        std::clamp((point.x - m_origin.x) / m_bucketSize, 0.0, static_cast<double>(m_columns - 1));
    const double row =
        std::clamp((point.y - m_origin.y) / m_bucketSize, 0.0, static_cast<double>(m_rows - 1));
    const std::uint32_t bucket =
        (*m_buckets)[static_cast<std::size_t>(row) * m_columns + static_cast<std::size_t>(column)];
    return bucket != kNoTriangle ? bucket : m_last;
}

namespace {

/// Whether `point` lies strictly right of a -> b by orient2d's floating-point stage alone: a
/// point within that stage's error bound of the line counts as on it.
bool surelyRight(Point2 a, Point2 b, Point2 point) {
    const double detLeft = (a.x - point.x) * (b.y - point.y);
    const double detRight = (a.y - point.y) * (b.x - point.x);
    return detLeft - detRight <
           -predicates::detail::kOrient2dErrorBoundA * (std::fabs(detLeft) + std::fabs(detRight));
}

} // namespace

std::optional<std::uint32_t> TinLocator::locate(Point2 point) {
    // Outside the box of the hull's vertices there is no triangle to walk to (the walk would
    // go as far as the hull to find that).
    if (m_buckets && (point.x < m_origin.x || point.y < m_origin.y || point.x > m_hullHigh.x ||
                      point.y > m_hullHigh.y))
        return std::nullopt;
    return walk(point, orient2dRight);
}

std::optional<std::uint32_t> TinLocator::locateNear(Point2 point) {
    return walk(point, surelyRight);
}

template <class OutsideOf>
std::optional<std::uint32_t> TinLocator::walk(Point2 point, OutsideOf outside) {
    const TinMesh& mesh = *m_mesh;
    const std::size_t triangles = mesh.triangleCount();
    if (triangles == 0)
        return std::nullopt;
    // From the last triangle when the point is near it (queries along a line), else from the
    // point's bucket.
    std::uint32_t t = m_last < triangles ? m_last : 0;
    const Point3& last = mesh.vertices[mesh.triangles[3 * t]];
    if (std::fabs(last.x - point.x) + std::fabs(last.y - point.y) > 2.0 * m_bucketSize)
        t = startNear(point);
    return walkFrom(t, point, outside);
}

std::optional<std::uint32_t> TinLocator::locateNearFrom(Point2 point, std::uint32_t start) {
    if (start >= m_mesh->triangleCount())
        return locateNear(point);
    return walkFrom(start, point, surelyRight);
}

template <class OutsideOf>
std::optional<std::uint32_t> TinLocator::walkFrom(std::uint32_t t, Point2 point,
                                                  OutsideOf outside) {
    const WalkEnd end = walkTowards(*m_mesh, t, point, outside, m_random);
    if (end.triangle)
        m_last = *end.triangle;
    return end.triangle;
}

std::optional<double> TinLocator::elevation(Point2 point) {
    const std::optional<std::uint32_t> triangle = locate(point);
    if (!triangle)
        return std::nullopt;
    return elevationIn(*triangle, point);
}

// The elevation must not depend on how the triangle is stored (which corner comes first) nor,
// for a point on an edge, on which of the edge's two triangles holds it: both follow the
// numbering of the triangles, which depends on the threads that built the TIN, and a constraint
// vertex's z would then differ in the last bit from one thread count to another. So the corners
// are taken from the one with the lowest index, a point at a vertex takes its z, and a point on
// an edge (exactly) is interpolated along the edge alone.
double TinLocator::elevationIn(std::uint32_t triangle, Point2 point) const {
    const TinMesh& mesh = *m_mesh;
    const std::array<std::uint32_t, 3> corners = cornersFromLowest(mesh, triangle);
    for (const std::uint32_t corner : corners)
        if (planar(mesh.vertices[corner]) == point)
            return mesh.vertices[corner].z;
    for (std::size_t i = 0; i < 3; ++i)
        if (const std::optional<double> z =
                elevationOnEdge(mesh, corners[i], corners[(i + 1) % 3], point))
            return *z;
    const Point3& a = mesh.vertices[corners[0]];
    const Point3& b = mesh.vertices[corners[1]];
    const Point3& c = mesh.vertices[corners[2]];
    const double area = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
    const double wa =
        ((b.x - point.x) * (c.y - point.y) - (b.y - point.y) * (c.x - point.x)) / area;
    const double wb =
        ((c.x - point.x) * (a.y - point.y) - (c.y - point.y) * (a.x - point.x)) / area;
    return wa * a.z + wb * b.z + (1.0 - wa - wb) * c.z;
}

} // namespace terratin

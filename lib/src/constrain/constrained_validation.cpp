#include "terratin/constrain/constrained_validation.hpp"

#include "terratin/geometry/predicates.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <unordered_set>

namespace terratin {

namespace {

constexpr std::size_t kMaxProblemsListed = 8;

// Unit roundoff, the scale of the area check's rounding bound.
constexpr double kUnitRoundoff = std::numeric_limits<double>::epsilon() / 2.0;

Point2 planar(const Point3& p) {
    return {p.x, p.y};
}

void report(ConstrainedValidation& result, std::size_t& counter, const std::string& problem) {
    ++counter;
    if (result.problems.size() < kMaxProblemsListed)
        result.problems.push_back(problem);
}

std::uint64_t edgeKey(std::uint32_t a, std::uint32_t b) {
    return a < b ? (std::uint64_t{a} << 32U) | b : (std::uint64_t{b} << 32U) | a;
}

// Twice the signed area of (a, b, c), and in `scale` the sum of its two products' magnitudes
// (what its rounding error is proportional to).
double twiceArea(const Point2& a, const Point2& b, const Point2& c, double& scale) {
    const double left = (b.x - a.x) * (c.y - a.y);
    const double right = (b.y - a.y) * (c.x - a.x);
    scale += std::fabs(left) + std::fabs(right);
    return left - right;
}

// Twice the convex hull's area (Andrew's monotone chain, exact orientation tests), adding to
// `scale` and `terms` what the rounding bound needs.
double twiceHullArea(const MeshArray<Point3>& vertices, double& scale, std::size_t& terms) {
    std::vector<Point2> sorted;
    sorted.reserve(vertices.size());
    for (const Point3& p : vertices)
        sorted.push_back(planar(p));
    std::sort(sorted.begin(), sorted.end(),
              [](const Point2& a, const Point2& b) { return a.x != b.x ? a.x < b.x : a.y < b.y; });
    sorted.erase(std::unique(sorted.begin(), sorted.end()), sorted.end());
    if (sorted.size() < 3)
        return 0.0;
    std::vector<Point2> hull(2 * sorted.size());
    std::size_t k = 0;
    for (const Point2& p : sorted) {
        while (k >= 2 && predicates::orient2d(hull[k - 2], hull[k - 1], p) <= 0.0)
            --k;
        hull[k++] = p;
    }
    const std::size_t lowerSize = k + 1;
    for (auto it = sorted.rbegin() + 1; it != sorted.rend(); ++it) {
        while (k >= lowerSize && predicates::orient2d(hull[k - 2], hull[k - 1], *it) <= 0.0)
            --k;
        hull[k++] = *it;
    }
    double area = 0.0;
    for (std::size_t i = 1; i + 2 < k; ++i)
        area += twiceArea(hull[0], hull[i], hull[i + 1], scale);
    terms += k;
    return area;
}

// The twin of half-edge 3t+i in triangle n, or -1.
int twinCorner(const TinMesh& mesh, std::size_t t, std::size_t i, std::size_t n) {
    const std::uint32_t from = mesh.triangles[3 * t + i];
    const std::uint32_t to = mesh.triangles[3 * t + (i + 1) % 3];
    for (int j = 0; j < 3; ++j)
        if (mesh.triangles[3 * n + static_cast<std::size_t>(j)] == to &&
            mesh.triangles[3 * n + static_cast<std::size_t>(j + 1) % 3] == from)
            return j;
    return -1;
}

bool sizesAndIndicesValid(const ConstrainedTin& tin, ConstrainedValidation& result) {
    const TinMesh& mesh = tin.mesh;
    if (mesh.triangles.size() % 3 != 0 || mesh.neighbours.size() != mesh.triangles.size() ||
        tin.constrained.size() != mesh.triangles.size()) {
        report(result, result.badIndices, "triangle, neighbour and flag arrays have wrong sizes");
        return false;
    }
    const auto triangleCount = static_cast<std::int64_t>(mesh.triangleCount());
    for (std::size_t k = 0; k < mesh.triangles.size(); ++k)
        if (mesh.triangles[k] >= mesh.vertexCount() || mesh.neighbours[k] >= triangleCount ||
            mesh.neighbours[k] < -1)
            report(result, result.badIndices, "index out of range at " + std::to_string(k));
    for (std::size_t c = 0; c < tin.chains.size(); ++c)
        for (const std::uint32_t v : tin.chains[c])
            if (v >= mesh.vertexCount())
                report(result, result.badIndices,
                       "chain " + std::to_string(c) + " names vertex " + std::to_string(v));
    return result.badIndices == 0;
}

// Orientation, twins, flags and the empty circle of unconstrained edges; returns the number
// of hull edges.
std::size_t checkTriangles(const ConstrainedTin& tin, ConstrainedValidation& result) {
    const TinMesh& mesh = tin.mesh;
    std::size_t hullEdges = 0;
    for (std::size_t t = 0; t < mesh.triangleCount(); ++t) {
        const std::uint32_t* corner = &mesh.triangles[3 * t];
        const Point2 a = planar(mesh.vertices[corner[0]]);
        const Point2 b = planar(mesh.vertices[corner[1]]);
        const Point2 c = planar(mesh.vertices[corner[2]]);
        if (predicates::orient2d(a, b, c) <= 0.0)
            report(result, result.notCounterClockwise,
                   "triangle " + std::to_string(t) + " is not counter-clockwise");
        for (std::size_t i = 0; i < 3; ++i) {
            const std::int32_t neighbour = mesh.neighbours[3 * t + i];
            if (neighbour < 0) {
                ++hullEdges;
                continue;
            }
            const auto n = static_cast<std::size_t>(neighbour);
            const int j = twinCorner(mesh, t, i, n);
            if (j < 0 || mesh.neighbours[3 * n + static_cast<std::size_t>(j)] != std::int32_t(t)) {
                report(result, result.asymmetricNeighbours,
                       "triangles " + std::to_string(t) + " and " + std::to_string(n) +
                           " are not mutual neighbours");
                continue;
            }
            const std::string edge =
                std::to_string(corner[i]) + "-" + std::to_string(corner[(i + 1) % 3]);
            const bool constrained = tin.constrained[3 * t + i] != 0;
            if (t < n && constrained != (tin.constrained[3 * n + static_cast<std::size_t>(j)] != 0))
                report(result, result.asymmetricFlags,
                       "edge " + edge + " is constrained on one side only");
            const Point2 opposite =
                planar(mesh.vertices[mesh.triangles[3 * n + static_cast<std::size_t>(j + 2) % 3]]);
            if (!constrained && predicates::incircle(a, b, c, opposite) > 0.0)
                report(result, result.nonDelaunayEdges,
                       "unconstrained edge " + edge + " is not locally Delaunay");
        }
    }
    return hullEdges;
}

void checkUseAndEuler(const TinMesh& mesh, std::size_t hullEdges, ConstrainedValidation& result) {
    std::vector<bool> used(mesh.vertexCount(), false);
    for (const std::uint32_t v : mesh.triangles)
        used[v] = true;
    for (std::size_t v = 0; v < used.size(); ++v)
        if (!used[v])
            report(result, result.unusedVertices, "vertex " + std::to_string(v) + " is unused");
    const std::size_t interiorHalfEdges = mesh.triangles.size() - hullEdges;
    const std::size_t edges = hullEdges + interiorHalfEdges / 2;
    result.eulerHolds =
        interiorHalfEdges % 2 == 0 && static_cast<std::int64_t>(mesh.vertexCount()) -
                                              static_cast<std::int64_t>(edges) +
                                              static_cast<std::int64_t>(mesh.triangleCount()) ==
                                          1;
    if (!result.eulerHolds && result.problems.size() < kMaxProblemsListed)
        result.problems.push_back("Euler's relation V - E + F = 1 does not hold");
}

// Equal up to the forward error bound of the two sums: each term is off by a few roundings of
// its products, and summing n terms adds at most n - 1 more, all relative to the magnitudes.
void checkArea(const TinMesh& mesh, ConstrainedValidation& result) {
    double scale = 0.0;
    std::size_t terms = mesh.triangleCount();
    double triangles = 0.0;
    for (std::size_t t = 0; t < mesh.triangleCount(); ++t)
        triangles += twiceArea(planar(mesh.vertices[mesh.triangles[3 * t]]),
                               planar(mesh.vertices[mesh.triangles[3 * t + 1]]),
                               planar(mesh.vertices[mesh.triangles[3 * t + 2]]), scale);
    const double hull = twiceHullArea(mesh.vertices, scale, terms);
    const double tolerance = 2.0 * static_cast<double>(terms + 8) * kUnitRoundoff * scale;
    result.areaMatchesHull = hull > 0.0 && std::fabs(triangles - hull) <= tolerance;
    if (!result.areaMatchesHull && result.problems.size() < kMaxProblemsListed)
        result.problems.push_back("triangle areas add up to " + std::to_string(triangles / 2) +
                                  ", the convex hull's area is " + std::to_string(hull / 2));
}

void checkChains(const ConstrainedTin& tin, ConstrainedValidation& result) {
    const TinMesh& mesh = tin.mesh;
    std::unordered_set<std::uint64_t> constrainedEdges;
    for (std::size_t h = 0; h < mesh.triangles.size(); ++h)
        if (tin.constrained[h] != 0)
            constrainedEdges.insert(
                edgeKey(mesh.triangles[h], mesh.triangles[h % 3 == 2 ? h - 2 : h + 1]));
    std::unordered_set<std::uint64_t> chainEdges;
    for (std::size_t c = 0; c < tin.chains.size(); ++c)
        for (std::size_t k = 1; k < tin.chains[c].size(); ++k) {
            const std::uint32_t a = tin.chains[c][k - 1];
            const std::uint32_t b = tin.chains[c][k];
            chainEdges.insert(edgeKey(a, b));
            if (!constrainedEdges.contains(edgeKey(a, b)))
                report(result, result.missingChainEdges,
                       "chain " + std::to_string(c) + ": no constrained edge " + std::to_string(a) +
                           "-" + std::to_string(b));
        }
    for (const std::uint64_t edge : constrainedEdges)
        if (!chainEdges.contains(edge))
            report(result, result.strayConstrainedEdges,
                   "constrained edge " + std::to_string(edge >> 32U) + "-" +
                       std::to_string(edge & 0xffffffffU) + " is on no chain");
}

} // namespace

ConstrainedValidation validateConstrainedDelaunay(const ConstrainedTin& tin) {
    ConstrainedValidation result;
    if (!sizesAndIndicesValid(tin, result))
        return result;
    const std::size_t hullEdges = checkTriangles(tin, result);
    checkUseAndEuler(tin.mesh, hullEdges, result);
    checkArea(tin.mesh, result);
    checkChains(tin, result);
    return result;
}

} // namespace terratin

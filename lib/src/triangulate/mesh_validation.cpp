#include "terratin/triangulate/mesh_validation.hpp"

#include "terratin/geometry/predicates.hpp"

#include <cstdint>
#include <unordered_map>

namespace terratin {

namespace {

constexpr std::size_t kMaxProblemsListed = 8;

Point2 planar(const Point3& p) {
    return {p.x, p.y};
}

void report(MeshValidation& result, std::size_t& counter, const std::string& problem) {
    ++counter;
    if (result.problems.size() < kMaxProblemsListed)
        result.problems.push_back(problem);
}

// Boundary edges a -> b (neighbour -1) must chain into one cycle a -> b -> c ... -> a in which
// every turn is left or straight.
void checkBoundary(const TinMesh& mesh, MeshValidation& result) {
    std::unordered_map<std::uint32_t, std::uint32_t> nextOnBoundary;
    const std::size_t triangleCount = mesh.triangleCount();
    for (std::size_t t = 0; t < triangleCount; ++t)
        for (std::size_t i = 0; i < 3; ++i)
            if (mesh.neighbours[3 * t + i] < 0) {
                const std::uint32_t a = mesh.triangles[3 * t + i];
                const std::uint32_t b = mesh.triangles[3 * t + (i + 1) % 3];
                if (!nextOnBoundary.emplace(a, b).second)
                    report(result, result.boundaryProblems,
                           "vertex " + std::to_string(a) + " starts two boundary edges");
            }
    if (nextOnBoundary.empty()) {
        report(result, result.boundaryProblems, "no boundary edge");
        return;
    }
    const std::uint32_t start = nextOnBoundary.begin()->first;
    std::uint32_t previous = start;
    std::size_t length = 0;
    for (;;) {
        const auto current = nextOnBoundary.find(previous);
        if (current == nextOnBoundary.end()) {
            report(result, result.boundaryProblems, "boundary is not closed");
            return;
        }
        const auto following = nextOnBoundary.find(current->second);
        if (following == nextOnBoundary.end()) {
            report(result, result.boundaryProblems, "boundary is not closed");
            return;
        }
        if (predicates::orient2d(planar(mesh.vertices[previous]),
                                 planar(mesh.vertices[current->second]),
                                 planar(mesh.vertices[following->second])) < 0.0)
            report(result, result.boundaryProblems,
                   "boundary turns right at vertex " + std::to_string(current->second));
        previous = current->second;
        ++length;
        if (previous == start || length > nextOnBoundary.size())
            break;
    }
    if (previous != start || length != nextOnBoundary.size())
        report(result, result.boundaryProblems, "boundary edges form more than one cycle");
}

// Array sizes and every index in range; false when the other checks cannot run.
bool checkIndices(const TinMesh& mesh, MeshValidation& result) {
    const std::size_t triangleCount = mesh.triangleCount();
    const std::size_t vertexCount = mesh.vertices.size();
    if (mesh.triangles.size() % 3 != 0 || mesh.neighbours.size() != mesh.triangles.size()) {
        report(result, result.badIndices, "triangle and neighbour arrays have wrong sizes");
        return false;
    }
    for (std::size_t k = 0; k < mesh.triangles.size(); ++k)
        if (mesh.triangles[k] >= vertexCount ||
            mesh.neighbours[k] >= static_cast<std::int64_t>(triangleCount) ||
            mesh.neighbours[k] < -1)
            report(result, result.badIndices, "index out of range at " + std::to_string(k));
    return result.badIndices == 0;
}

// The edge from corner i to corner i + 1 of triangle t, which has a neighbour: its twin in
// that neighbour must link back, and the neighbour's far corner must not lie strictly inside
// t's circumcircle.
void checkInteriorEdge(const TinMesh& mesh, std::size_t t, std::size_t i, MeshValidation& result) {
    const std::uint32_t* corner = &mesh.triangles[3 * t];
    const auto n = static_cast<std::size_t>(mesh.neighbours[3 * t + i]);
    // The twin: the edge corner[i+1] -> corner[i] of n, whose link points back to t.
    const std::uint32_t from = corner[i];
    const std::uint32_t to = corner[(i + 1) % 3];
    const std::uint32_t* other = &mesh.triangles[3 * n];
    int twin = -1;
    for (int j = 0; j < 3; ++j)
        if (other[j] == to && other[(j + 1) % 3] == from)
            twin = j;
    if (twin < 0 ||
        mesh.neighbours[3 * n + static_cast<std::size_t>(twin)] != static_cast<std::int32_t>(t)) {
        report(result, result.asymmetricNeighbours,
               "triangles " + std::to_string(t) + " and " + std::to_string(n) +
                   " are not mutual neighbours");
        return;
    }
    const Point2 opposite = planar(mesh.vertices[other[(twin + 2) % 3]]);
    if (predicates::incircle(planar(mesh.vertices[corner[0]]), planar(mesh.vertices[corner[1]]),
                             planar(mesh.vertices[corner[2]]), opposite) > 0.0)
        report(result, result.nonDelaunayEdges,
               "edge " + std::to_string(from) + "-" + std::to_string(to) +
                   " is not locally Delaunay");
}

// Every triangle counter-clockwise, every interior edge mutual and locally Delaunay, every
// vertex used. Returns the number of boundary edges.
std::size_t checkTriangles(const TinMesh& mesh, MeshValidation& result) {
    const std::size_t triangleCount = mesh.triangleCount();
    std::vector<bool> used(mesh.vertices.size(), false);
    std::size_t boundaryEdges = 0;
    for (std::size_t t = 0; t < triangleCount; ++t) {
        const std::uint32_t* corner = &mesh.triangles[3 * t];
        for (int i = 0; i < 3; ++i)
            used[corner[i]] = true;
        if (predicates::orient2d(planar(mesh.vertices[corner[0]]), planar(mesh.vertices[corner[1]]),
                                 planar(mesh.vertices[corner[2]])) <= 0.0)
            report(result, result.notCounterClockwise,
                   "triangle " + std::to_string(t) + " is not counter-clockwise");
        for (std::size_t i = 0; i < 3; ++i) {
            if (mesh.neighbours[3 * t + i] < 0)
                ++boundaryEdges;
            else
                checkInteriorEdge(mesh, t, i, result);
        }
    }
    for (std::size_t v = 0; v < used.size(); ++v)
        if (!used[v])
            report(result, result.unusedVertices, "vertex " + std::to_string(v) + " is unused");
    return boundaryEdges;
}

// Euler's relation V - E + F = 1 of a triangulated disk.
void checkEuler(const TinMesh& mesh, std::size_t boundaryEdges, MeshValidation& result) {
    const std::size_t triangleCount = mesh.triangleCount();
    // Each interior edge is seen twice, each boundary edge once.
    const std::size_t interiorHalfEdges = 3 * triangleCount - boundaryEdges;
    const std::size_t edges = boundaryEdges + interiorHalfEdges / 2;
    result.eulerHolds =
        interiorHalfEdges % 2 == 0 && static_cast<std::int64_t>(mesh.vertices.size()) -
                                              static_cast<std::int64_t>(edges) +
                                              static_cast<std::int64_t>(triangleCount) ==
                                          1;
    if (!result.eulerHolds && result.problems.size() < kMaxProblemsListed)
        result.problems.push_back("Euler's relation V - E + F = 1 does not hold");
}

} // namespace

MeshValidation validateDelaunay(const TinMesh& mesh) {
    MeshValidation result;
    if (!checkIndices(mesh, result))
        return result;
    const std::size_t boundaryEdges = checkTriangles(mesh, result);
    checkEuler(mesh, boundaryEdges, result);
    checkBoundary(mesh, result);
    return result;
}

} // namespace terratin

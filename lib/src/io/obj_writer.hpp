#pragma once
/// @file
/// ObjWriter: a TinMesh as a Wavefront OBJ for 3D tools.
///
/// OBJ has no CRS, and 3D tools work in single precision near the origin, so the vertices are
/// written relative to a local origin that the header records twice, for people and for
/// programs:
///   # CRS: <name> (EPSG:<code>)
///   # local origin: add (<x0>, <y0>, <z0>) to every vertex to get CRS coordinates
///   # terratin-origin <x0> <y0> <z0>
///   o <name>
///   v <x - x0> <y - y0> <z - z0>      one per vertex
///   f <a> <b> <c>                     1-based, counter-clockwise seen from above (+z)
/// The origin is chosen so that both the subtraction and the reader's addition are exact:
/// x0 = floor(min x) when (x - x0) + x0 == x holds for every vertex (it does for any
/// projected CRS, by Sterbenz's lemma, when min x > 0 and max x <= 2 x0), else 0; the same
/// for y; z0 = 0 (elevations are small already).

#include "buffered_file.hpp"
#include "terratin/triangulate/tin_mesh.hpp"
#include "writer_support.hpp"

#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>

namespace terratin::io::detail {

/// The exact local origin described above, of vertices seen one at a time in two passes:
/// every vertex to see(), then every vertex to check(), then origin().
class ObjOrigin {
public:
    void see(const Point3& p);
    void check(const Point3& p);
    [[nodiscard]] Point3 origin() const;

private:
    /// Per axis (x, y): the lowest value seen, and whether the candidate floor(lowest) has
    /// held for every vertex checked.
    std::array<double, 2> m_lowest{std::numeric_limits<double>::infinity(),
                                   std::numeric_limits<double>::infinity()};
    std::array<bool, 2> m_exact{true, true};
    [[nodiscard]] double candidate(std::size_t axis) const;
};

/// ObjOrigin of the mesh's vertices.
Point3 objLocalOrigin(const TinMesh& mesh);

/// The header's lines (before the first vertex) for `origin`; a vertex, relative to `origin`;
/// a face of vertices a, b, c (numbered from 0).
void putObjHead(BufferedFile& file, const MeshFileInfo& info, std::uint64_t vertexCount,
                std::uint64_t triangleCount, const Point3& origin);
void putObjVertex(BufferedFile& file, const Point3& p, const Point3& origin);
void putObjFace(BufferedFile& file, std::uint32_t a, std::uint32_t b, std::uint32_t c);

/// Writes the whole file; returns vertices + triangles. Throws IoError, Cancelled.
std::uint64_t writeObj(const TinMesh& mesh, const MeshFileInfo& info, BufferedFile& file,
                       const ProgressTicker& ticker);

} // namespace terratin::io::detail

#pragma once
/// @file
/// PlyWriter: a TinMesh as a binary little-endian Stanford PLY.
///
///   ply / format binary_little_endian 1.0
///   comment crs <one-line WKT>     (MDAL reads the rest of this line as the CRS)
///   element vertex V: property double x, y, z   (exact coordinates)
///   element face T: property list uchar int vertex_indices   (0-based, counter-clockwise)
/// The bytes are little-endian whatever the host.

#include "buffered_file.hpp"
#include "terratin/triangulate/tin_mesh.hpp"
#include "writer_support.hpp"

#include <cstdint>
#include <string>

namespace terratin::io::detail {

/// The header of a file of `vertexCount` vertices and `triangleCount` faces; InvalidInputError
/// when the vertices do not fit a PLY int index (2^31 - 1).
std::string plyHeader(const MeshFileInfo& info, std::uint64_t vertexCount,
                      std::uint64_t triangleCount);
/// One vertex record, and one face record of vertices a, b, c.
void putPlyVertex(BufferedFile& file, const Point3& p);
void putPlyFace(BufferedFile& file, std::uint32_t a, std::uint32_t b, std::uint32_t c);

/// Writes the whole file; returns vertices + triangles. Throws IoError, Cancelled, and
/// InvalidInputError for a mesh with more vertices than a PLY int index holds (2^31 - 1).
std::uint64_t writePly(const TinMesh& mesh, const MeshFileInfo& info, BufferedFile& file,
                       const ProgressTicker& ticker);

} // namespace terratin::io::detail

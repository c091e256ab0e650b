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

namespace terratin::io::detail {

/// Writes the whole file; returns vertices + triangles. Throws IoError, Cancelled, and
/// InvalidInputError for a mesh with more vertices than a PLY int index holds (2^31 - 1).
std::uint64_t writePly(const TinMesh& mesh, const MeshFileInfo& info, BufferedFile& file,
                       const ProgressTicker& ticker);

} // namespace terratin::io::detail

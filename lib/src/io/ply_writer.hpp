#pragma once
/// @file
/// PlyWriter: a TinMesh as a binary little-endian Stanford PLY.
///
///   ply / format binary_little_endian 1.0
///   comment crs <one-line WKT>     (MDAL reads the rest of this line as the CRS)
///   element vertex V: property double x, y, z   (exact coordinates)
///   element face T: property list uchar int vertex_indices   (0-based, counter-clockwise)
/// The bytes are little-endian whatever the host. A mesh of more vertices than a PLY int index
/// holds (2^31 - 1) is refused (InvalidInputError) when the head is written.

#include "mesh_writer.hpp"

namespace terratin::io::detail {

/// PLY's row of the format table.
extern const MeshWriter kPlyWriter;

} // namespace terratin::io::detail

#pragma once
/// @file
/// TwoDmWriter: a TinMesh as an SMS 2D mesh (.2dm), the text format QGIS opens as a mesh
/// layer through MDAL, with the node elevations as its "Bed Elevation" dataset.
///
///   MESH2D
///   MESHNAME "<name>"
///   ND <id> <x> <y> <z>          one per vertex, ids 1..V in vertex order
///   E3T <id> <n1> <n2> <n3> 1    one per triangle, ids 1..T, corners counter-clockwise,
///                                material 1
/// 2DM has no place for a CRS: the layer's CRS must be set in QGIS.

#include "buffered_file.hpp"
#include "terratin/triangulate/tin_mesh.hpp"
#include "writer_support.hpp"

#include <cstdint>

namespace terratin::io::detail {

/// The lines before the nodes; a node numbered `number` (from 0; its id is number + 1); an
/// element numbered `number` of vertices a, b, c (numbered from 0).
void putTwoDmHead(BufferedFile& file, const MeshFileInfo& info);
void putTwoDmNode(BufferedFile& file, std::uint64_t number, const Point3& p);
void putTwoDmElement(BufferedFile& file, std::uint64_t number, std::uint32_t a, std::uint32_t b,
                     std::uint32_t c);

/// Writes the whole file; returns vertices + triangles. Throws IoError, Cancelled.
std::uint64_t writeTwoDm(const TinMesh& mesh, const MeshFileInfo& info, BufferedFile& file,
                         const ProgressTicker& ticker);

} // namespace terratin::io::detail

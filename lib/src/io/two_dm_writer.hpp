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

#include "mesh_writer.hpp"

namespace terratin::io::detail {

/// 2DM's row of the format table.
extern const MeshWriter kTwoDmWriter;

} // namespace terratin::io::detail

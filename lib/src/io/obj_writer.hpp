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
/// for y; z0 = 0 (elevations are small already). The vertex records thus wait for every
/// vertex to have been seen twice (kVerticesAfterFigures).

#include "mesh_writer.hpp"

namespace terratin::io::detail {

/// OBJ's row of the format table.
extern const MeshWriter kObjWriter;

} // namespace terratin::io::detail

#pragma once
/// @file
/// The order in which GDAL's FlatGeobuf driver stores features behind its packed Hilbert
/// R-tree, so that the writer can hand them over already in that order.
///
/// GDAL 3.6 (ogr/ogrsf_frmts/flatgeobuf/packedrtree.cpp, hilbertSort) keys each feature by
/// the centre of its envelope, scaled into [0, 65535] over the envelope of all features:
///   x = floor(65535 * ((minX + maxX) / 2 - extentMinX) / extentWidth)   (0 when the width is 0)
/// and likewise y, and sorts by the index d(x, y) of that cell along the order-16 Hilbert
/// curve, in decreasing order. d is the classic curve (Butz; the iterative xy -> d of Hacker's
/// Delight / Wikipedia), which is the one GDAL's bit-twiddling formula computes: checked by
/// writing boxes through GDAL and reading back their order.
///
/// The driver sorts again whatever order it is given; features that arrive sorted only make
/// its sort touch memory in order. Getting this order wrong costs speed, never correctness.

#include "terratin/triangulate/tin_mesh.hpp"

#include <cstdint>
#include <vector>

namespace terratin::io::detail {

/// Index of cell (x, y) of the 65536 x 65536 grid along the Hilbert curve, in [0, 2^32).
std::uint32_t hilbertIndex16(std::uint32_t x, std::uint32_t y);

/// The triangles of `mesh` (indices into it) in the order GDAL's FlatGeobuf driver stores
/// them: decreasing Hilbert index of the centre of their x, y envelope; ties by triangle index.
/// Complexity: O(T log T) time with TBB, 16 bytes per triangle besides the result.
std::vector<std::uint32_t> packedRtreeOrder(const TinMesh& mesh);

/// A copy of `mesh` whose triangle i is triangle order[i] of `mesh`, corners in the same order
/// (the vertices are copied; sourceIndex and the neighbours, which refer to the old
/// numbering, are left empty). Enough for the writers, which read corners only.
/// Precondition: `order` is a permutation of the triangles of `mesh`.
TinMesh reorderTriangles(const TinMesh& mesh, const std::vector<std::uint32_t>& order);

} // namespace terratin::io::detail

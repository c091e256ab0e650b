#pragma once
/// @file
/// The attribute columns of the vector formats, and their values computed in parallel, one
/// chunk of triangles at a time, while the previous chunk is being written.

#include "terratin/geometry/triangle_attributes.hpp"
#include "terratin/io/tin_writer.hpp"
#include "terratin/triangulate/tin_mesh.hpp"

#include <cstddef>
#include <span>
#include <vector>

namespace terratin::io::detail {

/// One attribute column: its name (at most 10 characters, the DBF limit) and where its value is.
struct AttributeColumn {
    const char* name;
    double TriangleAttributes::*member;
};

/// The columns of `set`, in output order (empty for AttributeSet::None).
std::span<const AttributeColumn> attributeColumns(AttributeSet set);

/// Attributes of triangles [begin, end) into `out` (resized to end - begin), in parallel with
/// TBB. Corners are taken in mesh order, so z1 z2 z3 follow the counter-clockwise corners.
void computeAttributes(const TinMesh& mesh, std::size_t begin, std::size_t end,
                       std::vector<TriangleAttributes>& out);

} // namespace terratin::io::detail

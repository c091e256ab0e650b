#pragma once
/// @file
/// The convex hull of a grid's valid cell centres, the refiner's starting TIN.

#include "terratin/geometry/height_grid.hpp"
#include "terratin/geometry/point.hpp"

#include <cstdint>
#include <span>
#include <vector>

namespace terratin::detail {

/// Cells whose centres are the corners of the convex hull of the valid cells' centres in CRS
/// coordinates (HeightGrid::cellCentre), or at `positions[cell]` when `positions` is not
/// empty, counter-clockwise, without collinear points.
/// With the cell centres of a north-up geotransform (GT[4] = 0: every centre of a row has
/// exactly the same y), only each row's first and last valid cell can be a corner (every
/// other cell of the row lies between them), so the hull is built from at most 2 * height
/// candidates by Andrew's monotone chain with exact orientation tests. A rotated geotransform
/// (GT[2] or GT[4] != 0) rounds the centres of a row off their common line, by an ulp or so,
/// and a middle cell of the first or last row may then lie outside the segment between the
/// row's ends (a hull of the row ends would leave it "a point outside the hull"); there, as
/// with positions (a projection, which bends rows), the candidates are the valid cells with a
/// 4-neighbour outside the grid or without data: any other cell lies inside the quadrilateral
/// of its four neighbours' positions, by half a cell, for any map that is nearly affine at the
/// scale of a cell, as every map projection is at DEM resolutions. The hull is then the exact
/// hull of the rounded centres, whose border cells may be corners of it.
/// Throws InvalidInputError when there is no valid cell or all valid centres are collinear.
/// O(cells) to find the candidates.
std::vector<std::uint32_t> validHullCells(const HeightGrid& grid,
                                          std::span<const Point2> positions = {});

/// Whether `p` lies strictly outside the convex polygon `corners` (counter-clockwise, at least
/// three, no three collinear, as validHullCells gives them); a point on its boundary is
/// inside. Exact orientation tests, O(log corners): the wedge of the fan from corners[0]
/// that holds p is found by bisection, then p is tested against that wedge's outer edge.
bool outsideConvexPolygon(std::span<const Point2> corners, Point2 p);

} // namespace terratin::detail

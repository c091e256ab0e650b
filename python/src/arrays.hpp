#pragma once
/// @file
/// NumPy arrays in and out of the library, copying only when the memory layout demands it.
///
/// In: points as (N, 2) or (N, 3) arrays (PointsView) and a DEM as a 2-D array (heightGrid).
/// Out: a TinMesh's vertices and triangles as arrays that own the mesh's own buffers (meshArrays):
/// the std::vector moves into a capsule that frees it with the array, nothing is copied.

#include "terratin/geometry/height_grid.hpp"
#include "terratin/geometry/point.hpp"
#include "terratin/triangulate/tin_mesh.hpp"

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <array>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace terratin::python {

/// The points of an (N, 2) or (N, 3) array as Point3 (z = 0 for (N, 2)).
///
/// A C-contiguous, aligned, native-endian float64 (N, 3) array is used in place (Point3 is three
/// doubles); any other layout or real dtype (integers, float32, a strided view) is copied once
/// into Point3s, after NumPy's conversion to float64 for other dtypes; (N, 2) always needs that
/// copy, to add z. Throws InvalidInputError, naming `function`, for another number of
/// dimensions or columns and for a dtype that is not integer or floating point (bool, complex,
/// object, strings). The values themselves (finite, enough distinct points) are the library's
/// to check. Needs the GIL to construct; points() may then be read without it.
class PointsView {
public:
    PointsView(const pybind11::array& points, const std::string& function);

    [[nodiscard]] std::span<const Point3> points() const { return m_points; }

private:
    pybind11::array m_array; ///< the array viewed in place, kept alive
    std::vector<Point3> m_copy;
    std::span<const Point3> m_points;
};

/// A 2-D array of elevations (rows, columns: row 0 is the first stored row, as in a raster) as
/// a HeightGrid, with the rules of the raster reader: a cell is nodata when it is NaN or equal
/// to `nodata` compared in the array's own dtype (a float32 array compares with
/// float32(nodata), as GDAL's mask does; an integer array with the exact value, so a fractional
/// nodata matches none), and every other value becomes double and then the nearest float32
/// (HeightGrid::storeElevations). Any layout is read in place; dtypes other than the native
/// integer and float32/float64 ones are converted to float64 by NumPy first. Throws
/// InvalidInputError for another number of dimensions, a non-numeric dtype, more cells than
/// kMaxRefineCells, and a geotransform that geoTransformProblem refuses.
HeightGrid heightGrid(const pybind11::array& z, const std::array<double, 6>& geoTransform,
                      std::optional<double> nodata, const std::string& function);

/// (vertices, triangles): vertices a (V, 3) float64 array of x, y, z; triangles a (T, 3) array
/// of vertex indices, counter-clockwise, int32 (the mesh's own uint32 buffer, whose indices are
/// all below 2^31 then) or, for meshes of 2^31 vertices or more, int64 (a copy). Both arrays
/// own the mesh's buffers; `mesh` is left empty.
pybind11::tuple meshArrays(TinMesh&& mesh);

} // namespace terratin::python

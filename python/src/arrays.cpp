#include "arrays.hpp"

#include "terratin/error.hpp"
#include "terratin/refine/refine.hpp"

#include <climits>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <memory>
#include <type_traits>

namespace terratin::python {

namespace py = pybind11;

// A float64 (N, 3) array is read in place as Point3s: that needs three doubles and nothing else.
static_assert(std::is_standard_layout_v<Point3> && sizeof(Point3) == 3 * sizeof(double) &&
                  offsetof(Point3, x) == 0 && offsetof(Point3, y) == sizeof(double) &&
                  offsetof(Point3, z) == 2 * sizeof(double),
              "Point3 must be laid out as three consecutive doubles");

namespace {

std::string shapeText(const py::array& array) {
    return py::str(array.attr("shape")).cast<std::string>();
}

// NumPy's kinds 'i' (signed integer), 'u' (unsigned) and 'f' (floating point): the dtypes that
// hold coordinates or elevations. Bool, complex, object, strings and dates do not.
void requireRealDtype(const py::array& array, const std::string& function, const char* name) {
    const char kind = array.dtype().kind();
    if (kind != 'i' && kind != 'u' && kind != 'f')
        throw InvalidInputError(function + ": " + name +
                                " must hold integers or floating-point numbers, not dtype " +
                                py::str(array.dtype()).cast<std::string>());
}

bool holdsPoint3sInPlace(const py::array& points) {
    const int flags = points.flags();
    return points.shape(1) == 3 && points.dtype().equal(py::dtype::of<double>()) &&
           (flags & py::array::c_style) != 0 &&
           (flags & py::detail::npy_api::NPY_ARRAY_ALIGNED_) != 0;
}

// float64 `array` with the same shape: `array` itself when it is float64 already, whatever its
// layout; NumPy's conversion otherwise.
py::array_t<double> asFloat64(const py::array& array) {
    auto converted = py::array_t<double, py::array::forcecast>::ensure(array);
    if (!converted)
        throw py::error_already_set();
    return converted;
}

// Whether a cell of dtype T is nodata: NaN, or equal to the nodata value in T's own terms (see
// heightGrid).
template <class T> class NodataTest {
public:
    explicit NodataTest(std::optional<double> nodata) : m_nodata(nodata) {
        if constexpr (std::is_floating_point_v<T>) {
            // A nodata value beyond T's range matches no cell, as in GDAL's mask band.
            constexpr T kNoMatch = std::numeric_limits<T>::quiet_NaN();
            m_nodataAsT = nodata && (std::abs(*nodata) <= std::numeric_limits<T>::max() ||
                                     std::isinf(*nodata))
                              ? static_cast<T>(*nodata)
                              : kNoMatch;
        }
    }
    bool operator()(T value) const {
        if constexpr (std::is_floating_point_v<T>)
            return std::isnan(value) || value == m_nodataAsT;
        else
            return m_nodata && static_cast<double>(value) == *m_nodata;
    }

private:
    std::optional<double> m_nodata;
    T m_nodataAsT{};
};

// Stores the cells of `z` into `grid` row by row when z's dtype is T; false otherwise.
template <class T>
bool storeCellsAs(const py::array& z, std::optional<double> nodata, HeightGrid& grid) {
    if (!z.dtype().equal(py::dtype::of<T>()))
        return false;
    const auto cells = z.unchecked<T, 2>();
    const NodataTest<T> isNodata(nodata);
    constexpr double kNoData = std::numeric_limits<double>::quiet_NaN();
    std::vector<double> row(static_cast<std::size_t>(grid.width));
    for (py::ssize_t r = 0; r < cells.shape(0); ++r) {
        for (py::ssize_t c = 0; c < cells.shape(1); ++c) {
            const T value = cells(r, c);
            row[static_cast<std::size_t>(c)] =
                isNodata(value) ? kNoData : static_cast<double>(value);
        }
        grid.storeElevations(static_cast<std::size_t>(r) * row.size(), row);
    }
    return true;
}

void storeCells(const py::array& z, std::optional<double> nodata, HeightGrid& grid) {
    if (storeCellsAs<double>(z, nodata, grid) || storeCellsAs<float>(z, nodata, grid) ||
        storeCellsAs<std::int16_t>(z, nodata, grid) ||
        storeCellsAs<std::uint16_t>(z, nodata, grid) ||
        storeCellsAs<std::int32_t>(z, nodata, grid) ||
        storeCellsAs<std::uint32_t>(z, nodata, grid) ||
        storeCellsAs<std::int8_t>(z, nodata, grid) || storeCellsAs<std::uint8_t>(z, nodata, grid) ||
        storeCellsAs<std::int64_t>(z, nodata, grid) || storeCellsAs<std::uint64_t>(z, nodata, grid))
        return;
    // float16, long double, another byte order: as float64.
    storeCellsAs<double>(asFloat64(z), nodata, grid);
}

// A py::capsule that deletes `buffer` when the last array using it goes.
template <class Buffer> py::capsule ownerOf(std::unique_ptr<Buffer>& buffer) {
    py::capsule owner(buffer.get(), [](void* p) { delete static_cast<Buffer*>(p); });
    buffer.release();
    return owner;
}

py::array verticesArray(MeshArray<Point3>&& vertices) {
    auto owned = std::make_unique<MeshArray<Point3>>(std::move(vertices));
    const auto count = static_cast<py::ssize_t>(owned->size());
    const auto* data = reinterpret_cast<const double*>(owned->data());
    return py::array_t<double>(
        {count, py::ssize_t{3}},
        {static_cast<py::ssize_t>(sizeof(Point3)), static_cast<py::ssize_t>(sizeof(double))}, data,
        ownerOf(owned));
}

py::array trianglesArray(MeshArray<std::uint32_t>&& triangles, std::size_t vertexCount) {
    const auto count = static_cast<py::ssize_t>(triangles.size() / 3);
    if (vertexCount > static_cast<std::size_t>(std::numeric_limits<std::int32_t>::max())) {
        py::array_t<std::int64_t> wide({count, py::ssize_t{3}});
        std::int64_t* out = wide.mutable_data();
        for (std::size_t i = 0; i < triangles.size(); ++i)
            out[i] = triangles[i];
        return wide;
    }
    // Every index is below 2^31: the uint32 buffer reads as the same int32 values.
    auto owned = std::make_unique<MeshArray<std::uint32_t>>(std::move(triangles));
    const auto* data = reinterpret_cast<const std::int32_t*>(owned->data());
    constexpr auto kIndexBytes = static_cast<py::ssize_t>(sizeof(std::int32_t));
    return py::array_t<std::int32_t>({count, py::ssize_t{3}}, {3 * kIndexBytes, kIndexBytes}, data,
                                     ownerOf(owned));
}

} // namespace

PointsView::PointsView(const py::array& points, const std::string& function) {
    if (points.ndim() != 2 || (points.shape(1) != 2 && points.shape(1) != 3))
        throw InvalidInputError(function +
                                ": points must be an array of shape (N, 2) or (N, 3), not shape " +
                                shapeText(points));
    requireRealDtype(points, function, "points");
    const auto count = static_cast<std::size_t>(points.shape(0));
    // Rows 0 bytes apart are one point repeated (numpy.broadcast_to): refused before a copy
    // that could be larger than memory finds a single distinct point.
    if (count > 1 && points.strides(0) == 0)
        throw InvalidInputError(function + ": points holds one point repeated " +
                                std::to_string(count) +
                                " times (its rows are 0 bytes apart, as numpy.broadcast_to "
                                "makes them): fewer than three distinct points");
    if (holdsPoint3sInPlace(points)) {
        m_array = points;
        m_points = {static_cast<const Point3*>(points.data()), count};
        return;
    }
    const py::array_t<double> values = asFloat64(points);
    const auto view = values.unchecked<2>();
    const bool hasZ = points.shape(1) == 3;
    m_copy.resize(count);
    for (py::ssize_t i = 0; i < view.shape(0); ++i)
        m_copy[static_cast<std::size_t>(i)] = {view(i, 0), view(i, 1), hasZ ? view(i, 2) : 0.0};
    m_points = m_copy;
}

HeightGrid heightGrid(const py::array& z, const std::array<double, 6>& geoTransform,
                      std::optional<double> nodata, const std::string& function) {
    if (z.ndim() != 2)
        throw InvalidInputError(function + ": z must be a 2-D array (rows, columns), not shape " +
                                shapeText(z));
    requireRealDtype(z, function, "z");
    const py::ssize_t rows = z.shape(0);
    const py::ssize_t columns = z.shape(1);
    if (rows > INT_MAX || columns > INT_MAX ||
        static_cast<std::uint64_t>(rows) * static_cast<std::uint64_t>(columns) > kMaxRefineCells)
        throw InvalidInputError(function + ": z of shape " + shapeText(z) +
                                " has more cells than the refiner takes (" +
                                std::to_string(kMaxRefineCells) + ", each side below 2^31)");
    if (const std::string problem = geoTransformProblem(geoTransform, columns, rows);
        !problem.empty())
        throw InvalidInputError(function + ": the geotransform " + geoTransformText(geoTransform) +
                                " " + problem);
    HeightGrid grid;
    grid.width = static_cast<int>(columns);
    grid.height = static_cast<int>(rows);
    grid.geoTransform = geoTransform;
    grid.z.resize(grid.cellCount());
    storeCells(z, nodata, grid);
    return grid;
}

py::tuple meshArrays(TinMesh&& mesh) {
    const std::size_t vertexCount = mesh.vertexCount();
    py::array vertices = verticesArray(std::move(mesh.vertices));
    py::array triangles = trianglesArray(std::move(mesh.triangles), vertexCount);
    mesh = {};
    return py::make_tuple(std::move(vertices), std::move(triangles));
}

} // namespace terratin::python

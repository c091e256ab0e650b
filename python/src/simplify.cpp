/// @file
/// _terratin.simplify: terratin::refine on a DEM held in a NumPy array, then the same steps as
/// the build pipeline's simplification (lib/src/pipeline/build_pipeline.cpp, runRefineBuild)
/// for a raster whose CRS is kept: refine() on the cell centres, then dropLongEdgeTriangles
/// for max_edge. The TIN is the CLI's for the same raster and options.

#include "arrays.hpp"
#include "bindings.hpp"
#include "options.hpp"
#include "progress.hpp"

#include "terratin/error.hpp"
#include "terratin/refine/refine.hpp"
#include "terratin/tile/refine_tiles.hpp"
#include "terratin/triangulate/mesh_filter.hpp"

#include <pybind11/stl.h>

#include <array>
#include <cmath>
#include <optional>
#include <string>

namespace terratin::python {

namespace py = pybind11;

namespace {

const std::string kFunction = "terratin.simplify";

std::array<double, 6> geoTransformOption(const py::object& value) {
    const std::string expected =
        kFunction + ": geotransform must be 6 numbers in GDAL's order (x of the first cell's "
                    "corner, x per column, x per row, y of the corner, y per column, y per row)";
    if (!py::isinstance<py::sequence>(value) || py::isinstance<py::str>(value) ||
        py::len(value) != 6)
        throw InvalidInputError(expected);
    std::array<double, 6> coefficients{};
    const auto sequence = py::reinterpret_borrow<py::sequence>(value);
    for (std::size_t i = 0; i < coefficients.size(); ++i) {
        coefficients[i] = PyFloat_AsDouble(py::object(sequence[i]).ptr());
        if (coefficients[i] == -1.0 && PyErr_Occurred() != nullptr) {
            PyErr_Clear();
            throw InvalidInputError(expected);
        }
    }
    return coefficients;
}

// The options of refine(); the ranges are checked by checkRefineOptions.
struct SimplifyLimits {
    std::optional<double> maxError;
    std::optional<std::int64_t> maxPoints;
    std::optional<std::int64_t> maxTriangles;
    std::int64_t maxHole = 1;
    bool fillHoles = false;
    std::int64_t threads = 0;
    bool validate = false;
    std::int64_t tileSize = 0;
};

RefineOptions refineOptions(const SimplifyLimits& limits) {
    RefineOptions options;
    options.maxError = limits.maxError;
    if (limits.maxPoints)
        options.maxPoints = countOption(kFunction, "max_points", *limits.maxPoints);
    if (limits.maxTriangles)
        options.maxTriangles = countOption(kFunction, "max_triangles", *limits.maxTriangles);
    options.maxHole = countOption(kFunction, "max_hole", limits.maxHole);
    options.fillHoles = limits.fillHoles;
    options.threads = threadsOption(kFunction, limits.threads);
    options.validate = limits.validate;
    checkRefineOptions(options);
    return options;
}

TileOptions tileOptions(const SimplifyLimits& limits, const RefineOptions& refine) {
    TileOptions tiles;
    tiles.tileSize = countOption(kFunction, "tile_size", limits.tileSize);
    if (tiles.tileSize > 0)
        checkTileOptions(refine, tiles);
    return tiles;
}

py::tuple simplifyArray(const py::array& z, const py::object& geoTransform,
                        std::optional<double> nodata, const SimplifyLimits& limits,
                        std::optional<double> maxEdge, const py::object& progress) {
    const RefineOptions options = refineOptions(limits);
    const TileOptions tiles = tileOptions(limits, options);
    if (maxEdge && !(std::isfinite(*maxEdge) && *maxEdge > 0.0))
        throw InvalidInputError(kFunction + ": max_edge must be a positive length (CRS units)");
    HeightGrid grid = heightGrid(z, geoTransformOption(geoTransform), nodata, kFunction);
    TinMesh mesh = runWithoutGil(progress, [&](const ProgressCallback& callback) {
        RefineResult result = tiles.tileSize > 0 ? refineTiles(grid, options, tiles, callback)
                                                 : refine(grid, options, callback);
        grid = {}; // the mesh holds its own vertices
        if (maxEdge)
            dropLongEdgeTriangles(result.mesh, *maxEdge);
        return std::move(result.mesh);
    });
    return meshArrays(std::move(mesh));
}

} // namespace

void bindSimplify(py::module_& module) {
    using namespace py::literals;
    module.def(
        "simplify",
        [](const py::array& z, const py::object& geoTransform, std::optional<double> nodata,
           std::optional<double> maxError, std::optional<std::int64_t> maxPoints,
           std::optional<std::int64_t> maxTriangles, std::int64_t maxHole, bool fillHoles,
           std::optional<double> maxEdge, std::int64_t threads, bool validate,
           std::int64_t tileSize, const py::object& progress) {
            const SimplifyLimits limits{maxError,  maxPoints, maxTriangles, maxHole,
                                        fillHoles, threads,   validate,     tileSize};
            return simplifyArray(z, geoTransform, nodata, limits, maxEdge, progress);
        },
        "z"_a, "geotransform"_a, "nodata"_a = py::none(), "max_error"_a = py::none(),
        "max_points"_a = py::none(), py::kw_only(), "max_triangles"_a = py::none(),
        "max_hole"_a = 1, "fill_holes"_a = false, "max_edge"_a = py::none(), "threads"_a = 0,
        "validate"_a = false, "tile_size"_a = 0, "progress"_a = py::none(),
        "Error-bounded TIN of a DEM; see terratin.simplify.");
}

} // namespace terratin::python

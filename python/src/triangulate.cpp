/// @file
/// _terratin.triangulate: terratin::triangulate on a NumPy array of points.

#include "arrays.hpp"
#include "bindings.hpp"
#include "options.hpp"
#include "progress.hpp"

#include "terratin/triangulate/triangulate.hpp"

#include <chrono>
#include <string>

namespace terratin::python {

namespace py = pybind11;

namespace {

const std::string kFunction = "terratin.triangulate";

struct TimedMesh {
    py::tuple arrays; ///< (vertices, triangles)
    /// Wall-clock seconds of terratin::triangulate alone, without the Python call around it.
    double librarySeconds = 0.0;
};

/// Each vertex's row in the caller's points, as int64 (NumPy's index type).
py::array sourceRows(const MeshArray<std::uint32_t>& sourceIndex) {
    py::array_t<std::int64_t> rows(static_cast<py::ssize_t>(sourceIndex.size()));
    auto out = rows.mutable_unchecked<1>();
    for (std::size_t v = 0; v < sourceIndex.size(); ++v)
        out(static_cast<py::ssize_t>(v)) = sourceIndex[v];
    return rows;
}

TimedMesh triangulateArray(const py::array& points, const std::string& method, std::int64_t threads,
                           std::uint64_t seed, const py::object& progress,
                           bool returnIndex = false) {
    const PointsView view(points, kFunction);
    TriangulationOptions options;
    options.method = methodOption(kFunction, method);
    options.threads = threadsOption(kFunction, threads);
    options.seed = seed;
    double librarySeconds = 0.0;
    TriangulationResult result = runWithoutGil(progress, [&](const ProgressCallback& callback) {
        const auto start = std::chrono::steady_clock::now();
        TriangulationResult triangulation = triangulate(view.points(), options, callback);
        librarySeconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        return triangulation;
    });
    if (!returnIndex)
        return {meshArrays(std::move(result.mesh)), librarySeconds};
    py::array rows = sourceRows(result.mesh.sourceIndex);
    const py::tuple mesh = meshArrays(std::move(result.mesh));
    return {py::make_tuple(mesh[0], mesh[1], std::move(rows)), librarySeconds};
}

} // namespace

void bindTriangulate(py::module_& module) {
    using namespace py::literals;
    module.def(
        "triangulate",
        [](const py::array& points, const std::string& method, std::int64_t threads,
           std::uint64_t seed, const py::object& progress, bool returnIndex) {
            return triangulateArray(points, method, threads, seed, progress, returnIndex).arrays;
        },
        "points"_a, "method"_a = "auto", "threads"_a = 0, py::kw_only(), "seed"_a = 1,
        "progress"_a = py::none(), "return_index"_a = false,
        "Exact Delaunay triangulation; see terratin.triangulate.");
    // For python/bench/triangulate_bench.py: the Python call's cost against the library's own,
    // measured in the same call.
    module.def(
        "_triangulate_timed",
        [](const py::array& points, const std::string& method, std::int64_t threads) {
            TimedMesh timed = triangulateArray(points, method, threads, 1, py::none());
            return py::make_tuple(timed.arrays[0], timed.arrays[1], timed.librarySeconds);
        },
        "points"_a, "method"_a = "auto", "threads"_a = 0,
        "(vertices, triangles, seconds of terratin::triangulate alone).");
}

} // namespace terratin::python

#pragma once
/// @file
/// The parts of the extension module `terratin._terratin`, one function per topic, each adding
/// its names to the module. python/terratin/__init__.py is the public face; it re-exports them.

#include <pybind11/pybind11.h>

namespace terratin::python {

/// terratin.Error and its subclasses, mapped from the C++ hierarchy (terratin/error.hpp).
void bindErrors(pybind11::module_& module);

/// _terratin.triangulate(points, method, threads, seed, progress).
void bindTriangulate(pybind11::module_& module);

/// _terratin.simplify(z, geotransform, nodata, max_error, ..., progress).
void bindSimplify(pybind11::module_& module);

/// _terratin.build(inputs, output, progress, **options): the command line's build.
void bindBuild(pybind11::module_& module);

} // namespace terratin::python

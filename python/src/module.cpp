/// @file
/// The extension module `terratin._terratin`: terratin::core for Python, NumPy arrays in and
/// out, and terratin::io's build of files. docs/python.md describes the API;
/// python/terratin/__init__.py documents each function.

#include "bindings.hpp"

PYBIND11_MODULE(_terratin, module) {
    module.doc() = "terratin's C++ library: exact Delaunay TINs from arrays and from files.";
    module.attr("__version__") = TERRATIN_VERSION_TEXT;
    terratin::python::bindErrors(module);
    terratin::python::bindTriangulate(module);
    terratin::python::bindSimplify(module);
    terratin::python::bindBuild(module);
}

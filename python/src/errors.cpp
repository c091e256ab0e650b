/// @file
/// terratin's exception hierarchy as Python classes: terratin.Error (a RuntimeError) and its
/// subclasses InvalidInputError, IoError, CrsError and Cancelled. A C++ exception of one of
/// those types leaving a binding becomes the Python class of the same name, message unchanged.

#include "bindings.hpp"

#include "terratin/error.hpp"

namespace terratin::python {

namespace py = pybind11;

void bindErrors(py::module_& module) {
    // pybind11 tries the most recently registered translator first: the base goes first so that
    // each subclass is caught by its own translator, not by the base's.
    auto& error = py::register_exception<Error>(module, "Error", PyExc_RuntimeError);
    error.doc() = "Base of every error terratin raises; the message names the stage that failed.";
    py::register_exception<InvalidInputError>(module, "InvalidInputError", error).doc() =
        "The input is readable but unusable: a bad array, too few points, an option out of "
        "range.";
    py::register_exception<IoError>(module, "IoError", error).doc() =
        "A file could not be opened, read, written or renamed.";
    py::register_exception<CrsError>(module, "CrsError", error).doc() =
        "A coordinate reference system is missing, unknown or cannot be transformed.";
    py::register_exception<Cancelled>(module, "Cancelled", error).doc() =
        "The progress callable returned False.";
}

} // namespace terratin::python

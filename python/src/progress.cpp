#include "progress.hpp"

namespace terratin::python {

namespace py = pybind11;

bool ProgressBridge::report(double fraction, std::string_view message) {
    const py::gil_scoped_acquire gil;
    if (m_error)
        return false; // already stopping; the library may report once more on its way out
    try {
        if (PyErr_CheckSignals() != 0)
            throw py::error_already_set();
        if (m_callable.is_none())
            return true;
        const py::object keepGoing = m_callable(fraction, py::str(message.data(), message.size()));
        // None (a callable without a return statement) continues, as in GDAL's Python
        // bindings; anything else by its truth value.
        if (keepGoing.is_none())
            return true;
        const int truth = PyObject_IsTrue(keepGoing.ptr());
        if (truth < 0)
            throw py::error_already_set();
        return truth != 0;
    } catch (py::error_already_set& error) {
        m_error.emplace(std::move(error));
        return false;
    }
}

} // namespace terratin::python

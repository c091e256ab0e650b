#pragma once
/// @file
/// Running a library call without the GIL, with a Python progress callable and Ctrl-C.
///
/// The library calls its ProgressCallback from the calling thread a few times a second
/// (triangulate.hpp, refine.hpp). Each call takes the GIL back, runs pending signal handlers
/// (PyErr_CheckSignals: Ctrl-C raises KeyboardInterrupt there) and then the user's callable.
/// A Python exception from either, or a falsy return, makes the callback return false; the
/// library then throws terratin::Cancelled, and the Python exception, when there is one, is
/// raised in its place.

#include "terratin/error.hpp"
#include "terratin/progress.hpp"

#include <pybind11/pybind11.h>

#include <optional>
#include <string_view>
#include <utility>

namespace terratin::python {

/// The library's progress callback for one call, backed by a Python callable (or None).
/// Lives on the calling thread's stack for the duration of the call.
class ProgressBridge {
public:
    /// `callable(fraction, message) -> bool`; None reports nothing but still lets Ctrl-C cancel.
    explicit ProgressBridge(pybind11::object callable) : m_callable(std::move(callable)) {}

    /// The callback to hand to the library; it refers to this bridge.
    [[nodiscard]] ProgressCallback callback() {
        return
            [this](double fraction, std::string_view message) { return report(fraction, message); };
    }

    /// Raises the Python exception that stopped the library, if one did. Needs the GIL.
    void rethrowPythonError() const {
        if (m_error)
            throw *m_error;
    }

private:
    bool report(double fraction, std::string_view message);

    pybind11::object m_callable;
    std::optional<pybind11::error_already_set> m_error;
};

/// Returns work(progressCallback), run with the GIL released so that other Python threads run
/// meanwhile. `work` must not touch Python objects. A Cancelled caused by a Python exception
/// (KeyboardInterrupt, or one the callable raised) becomes that exception; other terratin
/// errors reach Python as terratin.Error subclasses (errors.cpp).
template <class Work> auto runWithoutGil(const pybind11::object& progress, Work&& work) {
    ProgressBridge bridge(progress);
    try {
        const pybind11::gil_scoped_release release;
        return std::forward<Work>(work)(bridge.callback());
    } catch (const Cancelled&) {
        bridge.rethrowPythonError();
        throw;
    }
}

} // namespace terratin::python

/// @file
/// _terratin.build: the command line's `terratin build` for a Python caller. The keyword
/// arguments become the option table's texts (build_option_table.hpp says how a binding turns
/// values into text) and go through parseBuildOptions with OptionSpelling::Keyword, so Python
/// gets the CLI's checks and messages, naming `max_error` where the CLI names `--max-error`.

#include "bindings.hpp"
#include "progress.hpp"
#include "termination_signals.hpp"

#include "terratin/error.hpp"
#include "terratin/pipeline/build_option_table.hpp"
#include "terratin/pipeline/build_pipeline.hpp"

#include <string>
#include <vector>

namespace terratin::python {

namespace py = pybind11;

namespace {

const std::string kFunction = "terratin.build";

/// A path given as str, bytes or os.PathLike, as text (os.fsdecode).
std::string pathText(const py::handle& value, const std::string& what) {
    try {
        return py::module_::import("os").attr("fsdecode")(value).cast<std::string>();
    } catch (const py::error_already_set& error) {
        if (!error.matches(PyExc_TypeError))
            throw;
        throw InvalidInputError(kFunction + ": " + what + " must be a path (str, bytes or " +
                                "os.PathLike), not " + std::string(py::str(value.get_type())));
    }
}

bool isPath(const py::handle& value) {
    return py::isinstance<py::str>(value) || py::isinstance<py::bytes>(value) ||
           py::hasattr(value, "__fspath__");
}

/// The inputs: one path, or any iterable of paths.
void addInputs(std::vector<OptionValue>& values, const py::handle& inputs) {
    const std::string name = optionName("inputs", OptionSpelling::Keyword);
    if (isPath(inputs)) {
        values.push_back({name, pathText(inputs, "inputs")});
        return;
    }
    if (!py::isinstance<py::iterable>(inputs))
        throw InvalidInputError(kFunction + ": inputs must be a path or a list of paths, not " +
                                std::string(py::str(inputs.get_type())));
    for (const py::handle item : py::reinterpret_borrow<py::iterable>(inputs))
        values.push_back({name, pathText(item, "each of inputs")});
}

/// A scalar's text: "true" / "false" for a bool (before int: True is an int in Python), the
/// path of an os.PathLike, str() of anything else (repr-exact for float).
std::string scalarText(const py::handle& value) {
    if (py::isinstance<py::bool_>(value))
        return value.cast<bool>() ? "true" : "false";
    if (py::hasattr(value, "__fspath__"))
        return pathText(value, "a path option");
    return py::str(value);
}

bool isList(const py::handle& value) {
    return py::isinstance<py::list>(value) || py::isinstance<py::tuple>(value);
}

/// One keyword argument as the option values it stands for; none for None (the default).
void addOption(std::vector<OptionValue>& values, const std::string& name, const py::handle& value) {
    if (value.is_none())
        return;
    const BuildOptionSpec* option = findBuildOption(name, OptionSpelling::Keyword);
    // An unknown name goes to the table too, which refuses it with a did-you-mean.
    const OptionKind kind = option != nullptr ? option->kind : OptionKind::Text;
    if (kind == OptionKind::Repeatable && isList(value)) {
        for (const py::handle item : value)
            values.push_back({name, scalarText(item)});
        return;
    }
    if (kind == OptionKind::List && isList(value)) {
        std::string joined;
        for (const py::handle item : value)
            joined += (joined.empty() ? "" : ",") + scalarText(item);
        values.push_back({name, joined});
        return;
    }
    values.push_back({name, scalarText(value)});
}

std::vector<OptionValue> optionValues(const py::handle& inputs, const py::handle& output,
                                      const py::kwargs& options) {
    std::vector<OptionValue> values;
    addInputs(values, inputs);
    // tiles_dir takes the place of the output (--tiles-dir instead of -o).
    if (!(output.is_none() && options.contains("tiles_dir")))
        values.push_back({"output", pathText(output, "output")});
    for (const auto& [name, value] : options)
        addOption(values, py::str(name), value);
    return values;
}

/// The report as JSON text: toJson, the CLI's --json.
std::string build(const py::object& inputs, const py::object& output, const py::object& progress,
                  const py::kwargs& options) {
    const BuildOptions build =
        parseBuildOptions(optionValues(inputs, output, options), OptionSpelling::Keyword);
    const TerminationSignals signals;
    try {
        std::string report = runWithoutGil(progress, [&](const ProgressCallback& callback) {
            return toJson(runBuild(build, signals.cancelling(callback)));
        });
        signals.reraiseIfReceived();
        return report;
    } catch (const Cancelled&) {
        // The run has removed its temporaries: now the signal may end the process.
        signals.reraiseIfReceived();
        throw;
    }
}

} // namespace

void bindBuild(py::module_& module) {
    using namespace py::literals;
    module.def("build", &build, "inputs"_a, "output"_a, py::kw_only(), "progress"_a = py::none(),
               "The command line's build; see terratin.build. Returns the JSON report.");
}

} // namespace terratin::python

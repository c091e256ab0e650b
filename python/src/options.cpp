#include "options.hpp"

#include "terratin/error.hpp"
#include "terratin/pipeline/build_option_table.hpp"

#include <algorithm>
#include <limits>
#include <string>

namespace terratin::python {

std::size_t countOption(const std::string& function, const char* option, std::int64_t value) {
    if (value < 0)
        throw InvalidInputError(function + ": " + option + " must be 0 or more (got " +
                                std::to_string(value) + ")");
    return static_cast<std::size_t>(value);
}

unsigned threadsOption(const std::string& function, std::int64_t value) {
    const std::size_t count = countOption(function, "threads", value);
    // Above kMaxThreads the library refuses it with its range; the clamp only keeps the value
    // from wrapping on its way there.
    return static_cast<unsigned>(
        std::min<std::size_t>(count, std::numeric_limits<unsigned>::max()));
}

TriangulationMethod methodOption(const std::string& function, const std::string& name) {
    // The option table's parser, so that the names and the message are the CLI's.
    BuildOptions parsed;
    try {
        applyBuildOption(parsed, {"method", name}, OptionSpelling::Keyword);
    } catch (const InvalidInputError& error) {
        throw InvalidInputError(function + ": " + error.markedMessage());
    }
    return parsed.triangulation.method;
}

} // namespace terratin::python

#pragma once
// Command-line parsing for `terratin`: Boost.Program_options, described from the library's
// option table, onto terratin::parseBuildOptions (terratin/pipeline/build_option_table.hpp).

#include "terratin/pipeline/build_pipeline.hpp"

#include <stdexcept>
#include <string>
#include <vector>

namespace terratin::cli {

/// A command line that cannot be understood; the CLI exits with status 2.
class UsageError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

/// What the user asked for.
struct Command {
    enum class Kind { Build, Help, Version, Formats };
    Kind kind = Kind::Help;
    /// Text to print for Help, and for Formats.
    std::string helpText;
    BuildOptions build;
    bool quiet = false;
    bool json = false;
};

/// Parses argv (without the program name). Throws UsageError with a one-line reason.
Command parseCommandLine(const std::vector<std::string>& arguments);

} // namespace terratin::cli

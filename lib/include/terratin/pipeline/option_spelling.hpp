#pragma once
/// @file
/// How a message names an option: the way its caller gave it.

namespace terratin {

/// The command line says `--max-error`, a keyword caller (C++, Python) says `max_error`. Messages
/// of the library name an option the caller's way (see optionName in build_option_table.hpp).
enum class OptionSpelling {
    /// `--max-error`, `--t_srs`, `INPUT`: the `terratin` command line.
    CommandLine,
    /// `max_error`, `t_srs`, `inputs`: the keyword arguments of a library or Python caller.
    Keyword,
};

} // namespace terratin

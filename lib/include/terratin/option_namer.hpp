#pragma once
/// @file
/// OptionNamer: how a message of the io module names a build option, its caller's way.

#include <functional>
#include <string>
#include <string_view>
#include <utility>

namespace terratin {

/// Turns the keyword of a build option ("overwrite", "z_field") into the name a message gives
/// it. The names of the options live in the pipeline's option table, above io, so io takes its
/// naming from its caller, as crs::crsFromUserInput takes its option's name: the pipeline hands
/// io optionNamer(spelling) (pipeline/build_option_table.hpp), which says "--overwrite" for the
/// command line. A default-constructed OptionNamer says the keyword itself, as a C++ or Python
/// caller writes it.
class OptionNamer {
public:
    /// Names every option by its keyword.
    OptionNamer() = default;
    /// Names options by `name(keyword)`; an empty `name` names them by their keyword.
    explicit OptionNamer(std::function<std::string(std::string_view keyword)> name)
        : m_name(std::move(name)) {}

    /// The name of the option whose keyword is `keyword`.
    std::string operator()(std::string_view keyword) const {
        return m_name ? m_name(keyword) : std::string(keyword);
    }

private:
    std::function<std::string(std::string_view keyword)> m_name;
};

} // namespace terratin

#pragma once
/// @file
/// Python argument values onto the library's option types. Only the conversions Python's types
/// need (a negative int where the library takes an unsigned count); the ranges themselves are
/// the library's to check (checkTriangulationOptions, checkRefineOptions).

#include "terratin/triangulate/triangulate.hpp"

#include <cstddef>
#include <cstdint>
#include <string>

namespace terratin::python {

/// `value` as a count; InvalidInputError naming `function` and `option` when negative.
std::size_t countOption(const std::string& function, const char* option, std::int64_t value);

/// `value` as a thread count (0 = all); InvalidInputError when negative or above any count
/// the library takes.
unsigned threadsOption(const std::string& function, std::int64_t value);

/// The method named by toString(TriangulationMethod) ("auto", "strips"...), parsed by the build
/// option table; InvalidInputError listing the names otherwise.
TriangulationMethod methodOption(const std::string& function, const std::string& name);

} // namespace terratin::python

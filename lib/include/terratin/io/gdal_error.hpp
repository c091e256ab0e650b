#pragma once
/// @file
/// Turning GDAL's error state into terratin exceptions at the place of the call.

#include "terratin/error.hpp"

#include <string>
#include <string_view>

namespace terratin::io {

/// The last GDAL/OGR/CPL error message, or "unknown GDAL error" when GDAL recorded none.
std::string lastGdalErrorMessage();

/// Throws IoError("<stage>: <what> '<path>': <last GDAL message>").
[[noreturn]] void throwGdalError(std::string_view stage, std::string_view what,
                                 std::string_view path);

/// Registers GDAL drivers once and routes GDAL's own messages away from stderr (terratin
/// reports errors itself, one line each). Safe to call many times, from any thread.
void initialiseGdal();

} // namespace terratin::io

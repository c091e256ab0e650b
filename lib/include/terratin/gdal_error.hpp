#pragma once
/// @file
/// Turning GDAL's error state into terratin exceptions at the place of the call. Part of
/// terratin::io, but beside error.hpp rather than in io/: crs calls GDAL too, and io uses crs,
/// so the piece both need sits below both.

#include "terratin/error.hpp"

#include <string>
#include <string_view>

namespace terratin {

/// The last GDAL/OGR/CPL error message on one line. When GDAL recorded none: the system's
/// message for errno when errno names a write failure (no space left on device, disk quota
/// exceeded, file too large, input/output error, read-only file system), else `fallback`, the
/// cause the caller knows, else "GDAL gave no reason".
std::string lastGdalErrorMessage(std::string_view fallback = {});

/// Throws IoError("<stage>: <what> '<path>': <lastGdalErrorMessage(fallback)>").
[[noreturn]] void throwGdalError(std::string_view stage, std::string_view what,
                                 std::string_view path, std::string_view fallback = {});

/// Registers GDAL drivers once and routes GDAL's own messages away from stderr (terratin
/// reports errors itself, one line each). Safe to call many times, from any thread.
void initialiseGdal();

} // namespace terratin

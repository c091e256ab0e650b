#pragma once
/// @file
/// The versions of the libraries terratin reads and writes through, as GDAL's programs name
/// theirs with --version: what a bug report needs to say.

#include <string>

namespace terratin::io {

/// "GDAL 3.6.2, PROJ 9.1.1, GeographicLib 2.1.2, SQLite 3.40.1": the versions in use at run
/// time (GDAL, PROJ and SQLite as their shared libraries report them; GeographicLib's headers,
/// which its library must match).
std::string libraryVersions();

} // namespace terratin::io

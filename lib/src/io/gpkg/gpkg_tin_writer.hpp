#pragma once
/// @file
/// The GeoPackage writer: OGR creates the file, its layers, their fields and CRS; the rows and
/// the R-tree spatial index then go straight into those tables through SQLite, because
/// GDAL 3.6's per-feature inserts and per-entry R*Tree inserts take most of a DEM -> TIN run
/// otherwise (see docs/benchmarks.md).
///
/// Atomicity: everything is written under a temporary name (see atomic_output.hpp) and renamed
/// into place when complete; with appendLayer the existing GeoPackage is copied under the
/// temporary name first and the copy extended, so a failure leaves the original as it was.

#include "terratin/io/tin_writer.hpp"

#include <filesystem>

namespace terratin::io::detail {

/// Writes the triangle layer (and the node and edge layers when asked) with their spatial
/// indexes. Preconditions are checked by writeTin. Throws IoError, InvalidInputError (an
/// existing layer without overwrite), Cancelled.
TinWriteResult writeGeoPackageTin(const TinMesh& mesh, const std::filesystem::path& output,
                                  const TinWriteOptions& options, const ProgressCallback& progress);

} // namespace terratin::io::detail

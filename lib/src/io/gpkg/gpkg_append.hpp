#pragma once
/// @file
/// Layers added to a user's existing GeoPackage in place, as one SQLite write transaction on
/// the file itself. SQLite's own locking keeps other writers out for its duration (and this
/// run waits for theirs), its journal or write-ahead log, whichever the file uses, makes the
/// change all or nothing, a hot journal a crashed writer left is rolled back before anything
/// is read, and committed data still in another program's WAL is read from there: nothing
/// another program wrote can be lost, and the file keeps its owner, mode and inode. OGR makes
/// the layers' definitions in a scratch GeoPackage beside it; the transaction copies them in
/// and writes the rows and R-tree as fast as into a new file.

#include "gpkg_layer_jobs.hpp"

#include <filesystem>
#include <vector>

namespace terratin::io::detail {

/// Adds `jobs`' layers to the GeoPackage `output`, replacing layers of the same names when
/// options.overwrite allows. Refuses, before writing: a file SQLite opens read-only (IoError),
/// one that is not a GeoPackage or fails SQLite's quick_check (InvalidInputError), an
/// existing layer without overwrite (InvalidInputError), a lock another program keeps past
/// options.lockWaitSeconds (IoError). Throws Cancelled through `ticker`, also while waiting.
TinWriteResult appendGeoPackageTin(const TinMesh& mesh, const std::filesystem::path& output,
                                   const TinWriteOptions& options,
                                   const std::vector<GpkgLayerJob>& jobs,
                                   const ProgressTicker& ticker);

} // namespace terratin::io::detail

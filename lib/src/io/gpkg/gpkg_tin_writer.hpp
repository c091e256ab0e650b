#pragma once
/// @file
/// The GeoPackage writer: OGR creates the file, its layers, their fields and CRS; the rows and
/// the R-tree spatial index then go straight into those tables through SQLite, because
/// GDAL 3.6's per-feature inserts and per-entry R*Tree inserts take most of a DEM -> TIN run
/// otherwise (see docs/benchmarks.md).
///
/// Atomicity: a new file is written under a temporary name (see atomic_output.hpp) and renamed
/// into place when complete. Layers added to an existing GeoPackage (appendLayer) go into the
/// file itself in one SQLite transaction, under SQLite's locks and journal (gpkg_append.hpp).

#include "sqlite_connection.hpp"

#include "terratin/io/tin_writer.hpp"

#include <cstdint>
#include <filesystem>
#include <string>

namespace terratin::io::detail {

/// SQLite page cache while writing a TIN, in KiB (a negative cache_size is KiB): enough for the
/// B-tree's right edge and the index tables; the rows themselves are written once.
inline constexpr int kGpkgPageCacheKiB = 16 * 1024;

/// Writes the triangle layer (and the node and edge layers when asked) with their spatial
/// indexes. Preconditions are checked by writeTin. Throws IoError, InvalidInputError (an
/// existing layer without overwrite), Cancelled.
TinWriteResult writeGeoPackageTin(const TinMesh& mesh, const std::filesystem::path& output,
                                  const TinWriteOptions& options, const ProgressCallback& progress);

/// The layers a TIN writes into a GeoPackage.
struct GpkgLayerNames {
    std::string triangles;
    std::string nodes; // empty: no node layer
    std::string edges; // empty: no edge layer
    /// Whether the node layer has row and col columns (the vertices' raster cells).
    bool nodeCells = false;
};

/// The layers `options` asks for.
GpkgLayerNames gpkgLayerNames(const TinWriteOptions& options);

/// OGR's part: the new file `temporary`, its layers, their fields and CRS, no row; SQLite
/// pages sized for `features` rows in all.
void createGpkgTinLayers(const std::filesystem::path& temporary, std::uint64_t features,
                         const GpkgLayerNames& names, const TinWriteOptions& options,
                         const std::filesystem::path& output);

/// Fast settings for a file nobody else sees until it is renamed: no rollback journal (a
/// failed write deletes the temporary file instead), no fsync per commit, one lock for the run.
void configureForBulkWriting(SqliteConnection& db);

/// Before a new file is renamed onto `output`: a journal or WAL left by an earlier SQLite
/// session on the old output would be replayed into the new file under the same name and
/// corrupt it. Removes them when the new file is `replacing` the old one (overwrite), or there
/// is none; not when the output appeared during the run (the rename refuses it, and they are
/// its own). Never used on a file that is updated in place.
void removeStaleJournals(const std::filesystem::path& output, bool replacing);

} // namespace terratin::io::detail

#pragma once
/// @file
/// The GeoPackage RTree Spatial Index extension (GeoPackage 1.2 annex F.3) of one geometry
/// column, written the way GDAL 3.8 and later write it: the R*Tree virtual table is created
/// empty and its shadow tables (_node, _parent, _rowid) are filled with a tree packed in
/// memory, instead of one R*Tree insert per feature (which is what GDAL 3.6 does). Then the
/// specification's triggers, which keep the index in step with later edits by QGIS or OGR,
/// and the gpkg_extensions row.
///
/// The trigger set follows the file's GeoPackage version (PRAGMA user_version): the 1.2/1.3
/// set (insert, update1-4, delete) that GDAL 3.6 writes and its validate_gpkg.py checks, or
/// the 1.4 set (insert, update2, update4-7, delete) for a 1.4 file.

#include "packed_rtree.hpp"
#include "sqlite_connection.hpp"

#include <cstdint>
#include <functional>
#include <string>

namespace terratin::io::detail {

/// Names of the indexed column.
struct IndexedColumn {
    std::string table;
    std::string geometryColumn;
    std::string fidColumn;
};

/// "rtree_<table>_<geometry column>".
std::string rtreeTableName(const IndexedColumn& column);

/// Creates and fills the index of `column` from `tree` (whose entry i is feature id i + 1),
/// inside the caller's transaction. `progress(done)` is called now and then with the entries
/// stored so far (it may throw to cancel). Throws IoError when SQLite fails.
void writeGpkgSpatialIndex(SqliteConnection& connection, const IndexedColumn& column,
                           const PackedRtree& tree,
                           const std::function<void(std::uint64_t)>& progress);

} // namespace terratin::io::detail

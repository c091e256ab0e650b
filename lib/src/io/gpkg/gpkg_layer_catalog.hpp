#pragma once
/// @file
/// A GeoPackage's catalogue of layers, edited in SQL on one connection, so that adding and
/// replacing layers of a user's file happens inside that connection's write transaction: the
/// feature table itself, and its rows in gpkg_contents, gpkg_geometry_columns,
/// gpkg_spatial_ref_sys, gpkg_extensions and GDAL's gpkg_ogr_contents, as GeoPackage 1.2 and
/// 1.4 lay them out (OGC 12-128r15 and r18, sections 1.1 and 2.1, annex F.3).

#include "sqlite_connection.hpp"

#include <filesystem>
#include <string>

namespace terratin::io::detail {

/// InvalidInputError "<stage>: cannot add layers to '<output>': it is not a GeoPackage (...)"
/// when the main database lacks gpkg_contents, gpkg_geometry_columns or gpkg_spatial_ref_sys.
void requireGeoPackage(SqliteConnection& db, const std::filesystem::path& output);

/// Whether `table` names a layer of the GeoPackage (case-insensitively, as SQLite names do).
bool hasLayer(SqliteConnection& db, const std::string& table);

/// Whether the database holds any table, view, index or trigger named `name`.
bool hasSchemaObject(SqliteConnection& db, const std::string& name);

/// Removes the layer `table`: its R-tree spatial indexes, the table with its triggers and
/// indexes, and its rows in the GeoPackage's own tables (contents, geometry columns,
/// extensions, data columns, metadata references, GDAL's feature counts). InvalidInputError
/// for a tile pyramid, which is not a TIN's to replace.
void dropLayer(SqliteConnection& db, const std::string& table, const std::filesystem::path& output);

/// Copies the definition of the layer `table` (no row) from the attached database `from`
/// into main: the table's SQL with its indexes and triggers, its contents and geometry
/// column rows, its extensions, and its CRS, which is matched to one main already has (by
/// authority and code, else by definition) or added under a free srs_id.
void copyLayerDefinition(SqliteConnection& db, const std::string& from, const std::string& table);

} // namespace terratin::io::detail

#include "gpkg_layer_catalog.hpp"

#include "../atomic_output.hpp"
#include "../ogr_dataset_support.hpp"
#include "terratin/error.hpp"

#include <array>
#include <optional>
#include <vector>

namespace terratin::io::detail {

namespace {

/// The GeoPackage's own tables that hold a row per layer, beside gpkg_contents, which the
/// others refer to and which goes last.
constexpr std::array kPerLayerTables = {"gpkg_extensions", "gpkg_data_columns",
                                        "gpkg_metadata_reference", "gpkg_ogr_contents",
                                        "gpkg_geometry_columns"};

bool hasTable(SqliteConnection& db, const std::string& schema, const std::string& table) {
    SqliteStatement query(db, "SELECT count(*) FROM " + quoteIdentifier(schema) +
                                  ".sqlite_master WHERE type = 'table' AND name = ?");
    query.bindText(1, table);
    return query.nextRow() && query.integerColumn(0) > 0;
}

bool hasColumn(SqliteConnection& db, const std::string& schema, const std::string& table,
               const std::string& column) {
    SqliteStatement query(db, "SELECT count(*) FROM pragma_table_info(?, ?) WHERE name = ?");
    query.bindText(1, table);
    query.bindText(2, schema);
    query.bindText(3, column);
    return query.nextRow() && query.integerColumn(0) > 0;
}

/// The text of the first column of the query's first row, bound to `value`; nullopt for none.
std::optional<std::string> firstText(SqliteConnection& db, const std::string& sql,
                                     const std::string& value) {
    SqliteStatement query(db, sql);
    query.bindText(1, value);
    if (!query.nextRow())
        return std::nullopt;
    return query.textColumn(0);
}

std::optional<std::int64_t> firstInteger(SqliteConnection& db, const std::string& sql,
                                         std::int64_t value) {
    SqliteStatement query(db, sql);
    query.bindInteger(1, value);
    if (!query.nextRow())
        return std::nullopt;
    return query.integerColumn(0);
}

/// The srs_id in main for the CRS `scratchId` of `from`, added when main has none like it.
/// Organisation "NONE" marks the undefined systems -1 and 0, which match by number only.
std::int64_t mainSrsId(SqliteConnection& db, const std::string& from, std::int64_t scratchId) {
    const std::string source = quoteIdentifier(from) + ".gpkg_spatial_ref_sys";
    const std::optional<std::int64_t> match = firstInteger(
        db,
        "SELECT m.srs_id FROM main.gpkg_spatial_ref_sys m, " + source +
            " s WHERE s.srs_id = ?1 AND ((upper(s.organization) != 'NONE' AND "
            "upper(m.organization) = upper(s.organization) AND "
            "m.organization_coordsys_id = s.organization_coordsys_id) OR "
            "m.definition = s.definition OR (s.srs_id IN (-1, 0) AND m.srs_id = s.srs_id)) "
            "ORDER BY m.srs_id = s.srs_id DESC LIMIT 1",
        scratchId);
    if (match)
        return *match;
    const bool taken =
        firstInteger(db, "SELECT 1 FROM main.gpkg_spatial_ref_sys WHERE srs_id = ?", scratchId)
            .has_value();
    const std::int64_t id =
        taken ? db.queryInteger("SELECT max(max(srs_id) + 1, 1) FROM main.gpkg_spatial_ref_sys")
              : scratchId;
    SqliteStatement insert(db, "INSERT INTO main.gpkg_spatial_ref_sys (srs_name, srs_id, "
                               "organization, organization_coordsys_id, definition, description) "
                               "SELECT srs_name, ?1, organization, organization_coordsys_id, "
                               "definition, description FROM " +
                                   source + " WHERE srs_id = ?2");
    insert.bindInteger(1, id);
    insert.bindInteger(2, scratchId);
    insert.run();
    // The WKT 2 definition of the CRS extension, where both files have its column.
    if (hasColumn(db, "main", "gpkg_spatial_ref_sys", "definition_12_063") &&
        hasColumn(db, from, "gpkg_spatial_ref_sys", "definition_12_063")) {
        SqliteStatement wkt2(db, "UPDATE main.gpkg_spatial_ref_sys SET definition_12_063 = "
                                 "(SELECT definition_12_063 FROM " +
                                     source + " WHERE srs_id = ?2) WHERE srs_id = ?1");
        wkt2.bindInteger(1, id);
        wkt2.bindInteger(2, scratchId);
        wkt2.run();
    }
    return id;
}

/// The table's SQL, then its indexes and triggers. GDAL's triggers that count features in
/// gpkg_ogr_contents are left out where main does not keep those counts.
void copySchema(SqliteConnection& db, const std::string& from, const std::string& table,
                bool mainCountsFeatures) {
    SqliteStatement objects(db, "SELECT sql FROM " + quoteIdentifier(from) +
                                    ".sqlite_master WHERE tbl_name = ? AND sql IS NOT NULL "
                                    "ORDER BY CASE type WHEN 'table' THEN 0 WHEN 'index' "
                                    "THEN 1 ELSE 2 END");
    objects.bindText(1, table);
    std::vector<std::string> statements;
    while (objects.nextRow())
        statements.push_back(objects.textColumn(0));
    for (const std::string& sql : statements)
        if (mainCountsFeatures || sql.find("gpkg_ogr_contents") == std::string::npos)
            db.execute(sql);
}

void copyCatalogueRows(SqliteConnection& db, const std::string& from, const std::string& table,
                       std::int64_t srsId) {
    const std::string source = quoteIdentifier(from) + ".";
    // The identifier is unique among the file's layers: a clash keeps the table name alone.
    SqliteStatement contents(
        db, "INSERT INTO main.gpkg_contents (table_name, data_type, identifier, description, "
            "last_change, min_x, min_y, max_x, max_y, srs_id) SELECT table_name, data_type, "
            "CASE WHEN EXISTS (SELECT 1 FROM main.gpkg_contents m WHERE m.identifier = "
            "s.identifier) THEN NULL ELSE identifier END, description, last_change, min_x, "
            "min_y, max_x, max_y, ?1 FROM " +
                source + "gpkg_contents s WHERE table_name = ?2");
    contents.bindInteger(1, srsId);
    contents.bindText(2, table);
    contents.run();
    SqliteStatement geometry(db, "INSERT INTO main.gpkg_geometry_columns (table_name, "
                                 "column_name, geometry_type_name, srs_id, z, m) SELECT "
                                 "table_name, column_name, geometry_type_name, ?1, z, m FROM " +
                                     source + "gpkg_geometry_columns WHERE table_name = ?2");
    geometry.bindInteger(1, srsId);
    geometry.bindText(2, table);
    geometry.run();
}

void copyExtensions(SqliteConnection& db, const std::string& from, const std::string& table) {
    if (!hasTable(db, from, "gpkg_extensions"))
        return;
    db.execute("CREATE TABLE IF NOT EXISTS main.gpkg_extensions (table_name TEXT, column_name "
               "TEXT, extension_name TEXT NOT NULL, definition TEXT NOT NULL, scope TEXT NOT "
               "NULL, CONSTRAINT ge_tce UNIQUE (table_name, column_name, extension_name))");
    SqliteStatement extensions(db, "INSERT INTO main.gpkg_extensions (table_name, column_name, "
                                   "extension_name, definition, scope) SELECT table_name, "
                                   "column_name, extension_name, definition, scope FROM " +
                                       quoteIdentifier(from) +
                                       ".gpkg_extensions WHERE table_name = ?");
    extensions.bindText(1, table);
    extensions.run();
}

} // namespace

void requireGeoPackage(SqliteConnection& db, const std::filesystem::path& output) {
    for (const char* table : {"gpkg_contents", "gpkg_geometry_columns", "gpkg_spatial_ref_sys"})
        if (!hasTable(db, "main", table))
            throw InvalidInputError(std::string(kOgrStage) + ": cannot add layers to " +
                                    quoted(output) + ": it is not a GeoPackage (it has no " +
                                    table + " table)");
}

bool hasLayer(SqliteConnection& db, const std::string& table) {
    return firstText(db,
                     "SELECT table_name FROM main.gpkg_contents WHERE lower(table_name) = "
                     "lower(?)",
                     table)
        .has_value();
}

bool hasSchemaObject(SqliteConnection& db, const std::string& name) {
    return firstText(db, "SELECT name FROM main.sqlite_master WHERE lower(name) = lower(?)", name)
        .has_value();
}

void dropLayer(SqliteConnection& db, const std::string& table,
               const std::filesystem::path& output) {
    const std::optional<std::string> dataType = firstText(
        db, "SELECT data_type FROM main.gpkg_contents WHERE lower(table_name) = lower(?)", table);
    if (dataType && *dataType != "features" && *dataType != "attributes")
        throw InvalidInputError(std::string(kOgrStage) + ": the layer '" + table + "' of " +
                                quoted(output) + " is a " + *dataType +
                                " table, not one a TIN replaces; choose another layer name");
    const std::string stored =
        firstText(db,
                  "SELECT table_name FROM main.gpkg_contents WHERE lower(table_name) = lower(?)",
                  table)
            .value_or(table);

    if (hasTable(db, "main", "gpkg_extensions")) {
        SqliteStatement indexes(db, "SELECT column_name FROM main.gpkg_extensions WHERE "
                                    "lower(table_name) = lower(?) AND extension_name = "
                                    "'gpkg_rtree_index'");
        indexes.bindText(1, stored);
        std::vector<std::string> columns;
        while (indexes.nextRow())
            columns.push_back(indexes.textColumn(0));
        for (const std::string& column : columns)
            db.execute("DROP TABLE IF EXISTS main." +
                       quoteIdentifier("rtree_" + stored + "_" + column));
    }
    const std::optional<std::string> kind =
        firstText(db, "SELECT type FROM main.sqlite_master WHERE lower(name) = lower(?)", stored);
    if (kind == "table" || kind == "view")
        db.execute("DROP " + *kind + " main." + quoteIdentifier(stored));
    for (const char* catalogue : kPerLayerTables) {
        if (!hasTable(db, "main", catalogue))
            continue;
        SqliteStatement remove(db, std::string("DELETE FROM main.") + catalogue +
                                       " WHERE lower(table_name) = lower(?)");
        remove.bindText(1, stored);
        remove.run();
    }
    SqliteStatement contents(db,
                             "DELETE FROM main.gpkg_contents WHERE lower(table_name) = lower(?)");
    contents.bindText(1, stored);
    contents.run();
}

void copyLayerDefinition(SqliteConnection& db, const std::string& from, const std::string& table) {
    const std::optional<std::string> scratchSrs =
        firstText(db,
                  "SELECT srs_id FROM " + quoteIdentifier(from) +
                      ".gpkg_geometry_columns WHERE table_name = ?",
                  table);
    if (!scratchSrs)
        db.fail("no layer definition '" + table + "' to copy");
    const std::int64_t scratchSrsId = std::stoll(*scratchSrs);

    const bool countsFeatures =
        hasTable(db, "main", "gpkg_ogr_contents") && hasTable(db, from, "gpkg_ogr_contents");
    copySchema(db, from, table, countsFeatures);
    copyCatalogueRows(db, from, table, mainSrsId(db, from, scratchSrsId));
    copyExtensions(db, from, table);
    if (countsFeatures) {
        SqliteStatement count(
            db, "INSERT INTO main.gpkg_ogr_contents (table_name, feature_count) VALUES (?, 0)");
        count.bindText(1, table);
        count.run();
    }
}

} // namespace terratin::io::detail

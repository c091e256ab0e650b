#include "gpkg_spatial_index.hpp"

#include "batched_insert.hpp"

#include <string>

namespace terratin::io::detail {

namespace {

/// PRAGMA user_version of a GeoPackage 1.4 file.
constexpr std::int64_t kGeoPackage14 = 10400;
/// Rows stored between two progress reports.
constexpr std::uint64_t kProgressRows = 65'536;

/// The quoted names the trigger texts are made of.
struct TriggerNames {
    std::string rtree;       // "rtree_t_c"
    std::string table;       // "t"
    std::string geom;        // "c"
    std::string fid;         // "fid"
    std::string rtreePrefix; // rtree_t_c, unquoted, for the trigger names
};

std::string trigger(const TriggerNames& n, const std::string& suffix, const std::string& when,
                    const std::string& body) {
    return "CREATE TRIGGER " + quoteIdentifier(n.rtreePrefix + "_" + suffix) + " AFTER " + when +
           " BEGIN " + body + " END;";
}

std::string newBoxValues(const TriggerNames& n) {
    const std::string g = "NEW." + n.geom;
    return "VALUES (NEW." + n.fid + ", ST_MinX(" + g + "), ST_MaxX(" + g + "), ST_MinY(" + g +
           "), ST_MaxY(" + g + "))";
}

/// "(g NOTNULL AND NOT ST_IsEmpty(g))": the row has a box to index.
std::string hasBox(const std::string& geometry) {
    return "(" + geometry + " NOTNULL AND NOT ST_IsEmpty(" + geometry + "))";
}

/// "(g ISNULL OR ST_IsEmpty(g))": the row has no box.
std::string hasNoBox(const std::string& geometry) {
    return "(" + geometry + " ISNULL OR ST_IsEmpty(" + geometry + "))";
}

/// The triggers of GeoPackage 1.2 annex F.3; 1.4 replaces update1 by update6 and update7 (an
/// UPDATE of the box, or an INSERT when there was none) and renames update3 to update5.
std::string triggerSql(const TriggerNames& n, bool geoPackage14) {
    const std::string newGeom = "NEW." + n.geom;
    const std::string oldGeom = "OLD." + n.geom;
    const std::string sameFid = "OLD." + n.fid + " = NEW." + n.fid;
    const std::string otherFid = "OLD." + n.fid + " != NEW." + n.fid;
    const std::string updateOfGeom = "UPDATE OF " + n.geom + " ON " + n.table + " WHEN ";
    const std::string updateOfAny = "UPDATE ON " + n.table + " WHEN ";
    const std::string deleteOld = "DELETE FROM " + n.rtree + " WHERE id = OLD." + n.fid + ";";
    const std::string upsertNew = "INSERT OR REPLACE INTO " + n.rtree + " " + newBoxValues(n) + ";";

    std::string sql =
        trigger(n, "insert", "INSERT ON " + n.table + " WHEN " + hasBox(newGeom), upsertNew);
    if (geoPackage14) {
        const std::string sameFidNewBox = sameFid + " AND " + hasBox(newGeom) + " AND ";
        sql += trigger(n, "update6", updateOfGeom + sameFidNewBox + hasBox(oldGeom),
                       "UPDATE " + n.rtree + " SET minx = ST_MinX(" + newGeom +
                           "), maxx = ST_MaxX(" + newGeom + "), miny = ST_MinY(" + newGeom +
                           "), maxy = ST_MaxY(" + newGeom + ") WHERE id = NEW." + n.fid + ";");
        sql += trigger(n, "update7", updateOfGeom + sameFidNewBox + hasNoBox(oldGeom),
                       "INSERT INTO " + n.rtree + " " + newBoxValues(n) + ";");
    } else {
        sql += trigger(n, "update1", updateOfGeom + sameFid + " AND " + hasBox(newGeom), upsertNew);
    }
    sql += trigger(n, "update2", updateOfGeom + sameFid + " AND " + hasNoBox(newGeom), deleteOld);
    sql += trigger(n, geoPackage14 ? "update5" : "update3",
                   updateOfAny + otherFid + " AND " + hasBox(newGeom), deleteOld + " " + upsertNew);
    sql +=
        trigger(n, "update4", updateOfAny + otherFid + " AND " + hasNoBox(newGeom),
                "DELETE FROM " + n.rtree + " WHERE id IN (OLD." + n.fid + ", NEW." + n.fid + ");");
    sql +=
        trigger(n, "delete", "DELETE ON " + n.table + " WHEN " + oldGeom + " NOT NULL", deleteOld);
    return sql;
}

void registerExtension(SqliteConnection& connection, const IndexedColumn& column) {
    connection.execute(
        "CREATE TABLE IF NOT EXISTS gpkg_extensions (table_name TEXT, column_name TEXT, "
        "extension_name TEXT NOT NULL, definition TEXT NOT NULL, scope TEXT NOT NULL, "
        "CONSTRAINT ge_tce UNIQUE (table_name, column_name, extension_name))");
    connection.execute(
        "INSERT INTO gpkg_extensions (table_name, column_name, extension_name, definition, "
        "scope) VALUES (" +
        quoteLiteral(column.table) + ", " + quoteLiteral(column.geometryColumn) +
        ", 'gpkg_rtree_index', 'http://www.geopackage.org/spec120/#extension_rtree', "
        "'write-only')");
}

void storeNodes(SqliteConnection& connection, const std::string& rtree, const PackedRtree& tree) {
    // CREATE VIRTUAL TABLE stored an empty root; the packed tree brings its own.
    connection.execute("DELETE FROM " + quoteIdentifier(rtree + "_node"));
    SqliteStatement node(connection,
                         "INSERT INTO " + quoteIdentifier(rtree + "_node") + " VALUES (?, ?)");
    SqliteStatement parent(connection,
                           "INSERT INTO " + quoteIdentifier(rtree + "_parent") + " VALUES (?, ?)");
    tree.forEachNode([&](const PackedRtree::Node& stored) {
        node.bindInteger(1, stored.number);
        node.bindBlob(2, stored.blob);
        node.run();
        if (stored.parent != 0) {
            parent.bindInteger(1, stored.number);
            parent.bindInteger(2, stored.parent);
            parent.run();
        }
    });
}

void storeRowids(SqliteConnection& connection, const std::string& rtree, const PackedRtree& tree,
                 const std::function<void(std::uint64_t)>& progress) {
    const std::vector<std::int64_t> leafOf = tree.leafOfEntry();
    BatchedInsert rowids(connection, rtree + "_rowid", {"rowid", "nodeno"});
    const auto bindRowid = [&](std::size_t base) {
        return [&leafOf, base](SqliteStatement& statement, int parameter, std::size_t row) {
            statement.bindInteger(parameter, static_cast<std::int64_t>(base + row) + 1);
            statement.bindInteger(parameter + 1, leafOf[base + row]);
        };
    };
    for (std::size_t base = 0; base < leafOf.size(); base += kProgressRows) {
        progress(base);
        rowids.insert(std::min<std::size_t>(kProgressRows, leafOf.size() - base), bindRowid(base));
    }
}

} // namespace

std::string rtreeTableName(const IndexedColumn& column) {
    return "rtree_" + column.table + "_" + column.geometryColumn;
}

void writeGpkgSpatialIndex(SqliteConnection& connection, const IndexedColumn& column,
                           const PackedRtree& tree,
                           const std::function<void(std::uint64_t)>& progress) {
    const std::string rtree = rtreeTableName(column);
    connection.execute("CREATE VIRTUAL TABLE " + quoteIdentifier(rtree) +
                       " USING rtree(id, minx, maxx, miny, maxy)");
    if (tree.entryCount() > 0) {
        storeNodes(connection, rtree, tree);
        storeRowids(connection, rtree, tree, progress);
    }
    const TriggerNames names{quoteIdentifier(rtree), quoteIdentifier(column.table),
                             quoteIdentifier(column.geometryColumn),
                             quoteIdentifier(column.fidColumn), rtree};
    const bool geoPackage14 = connection.queryInteger("PRAGMA user_version") >= kGeoPackage14;
    connection.execute(triggerSql(names, geoPackage14));
    registerExtension(connection, column);
    progress(tree.entryCount());
}

} // namespace terratin::io::detail

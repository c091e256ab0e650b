#include "gpkg_feature_table.hpp"

namespace terratin::io::detail {

GpkgFeatureTable::GpkgFeatureTable(SqliteConnection& connection, std::string table)
    : m_connection(&connection), m_table(std::move(table)) {
    {
        SqliteStatement geometry(connection,
                                 "SELECT column_name, srs_id FROM gpkg_geometry_columns WHERE "
                                 "lower(table_name) = lower(?)");
        geometry.bindText(1, m_table);
        if (!geometry.nextRow())
            connection.fail("no feature table '" + m_table + "'");
        m_geometryColumn = geometry.textColumn(0);
        m_srsId = static_cast<std::int32_t>(geometry.integerColumn(1));
    }
    std::vector<std::string> names;
    {
        SqliteStatement triggers(connection, "SELECT name, sql FROM sqlite_master WHERE "
                                             "type = 'trigger' AND lower(tbl_name) = lower(?)");
        triggers.bindText(1, m_table);
        while (triggers.nextRow()) {
            names.push_back(triggers.textColumn(0));
            m_triggerSql.push_back(triggers.textColumn(1));
        }
    }
    for (const auto& name : names)
        connection.execute("DROP TRIGGER " + quoteIdentifier(name));
}

void GpkgFeatureTable::finish(std::uint64_t features, const Extent2d& extent) {
    for (const auto& sql : m_triggerSql)
        m_connection->execute(sql);
    if (features > 0) {
        SqliteStatement contents(
            *m_connection, "UPDATE gpkg_contents SET min_x = ?, min_y = ?, max_x = ?, max_y = ?, "
                           "last_change = strftime('%Y-%m-%dT%H:%M:%fZ', 'now') WHERE "
                           "lower(table_name) = lower(?)");
        contents.bindReal(1, extent.minX);
        contents.bindReal(2, extent.minY);
        contents.bindReal(3, extent.maxX);
        contents.bindReal(4, extent.maxY);
        contents.bindText(5, m_table);
        contents.run();
    }
    const bool hasOgrContents =
        m_connection->queryInteger("SELECT count(*) FROM sqlite_master WHERE type = 'table' AND "
                                   "name = 'gpkg_ogr_contents'") > 0;
    if (hasOgrContents) {
        SqliteStatement count(*m_connection, "UPDATE gpkg_ogr_contents SET feature_count = ? "
                                             "WHERE lower(table_name) = lower(?)");
        count.bindInteger(1, static_cast<std::int64_t>(features));
        count.bindText(2, m_table);
        count.run();
    }
}

} // namespace terratin::io::detail

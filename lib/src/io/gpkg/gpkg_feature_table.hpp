#pragma once
/// @file
/// GpkgFeatureTable: rows written straight into a feature table that OGR created, with the
/// bookkeeping OGR would have done around its own inserts.
///
/// While the rows go in, the table's triggers are set aside (OGR creates one that counts
/// features in gpkg_ogr_contents, one UPDATE per inserted row) and put back unchanged
/// afterwards; then the layer's extent in gpkg_contents and its count in gpkg_ogr_contents are
/// set as OGR sets them.

#include "sqlite_connection.hpp"

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace terratin::io::detail {

/// A planar extent, in CRS units.
struct Extent2d {
    double minX = 0.0;
    double minY = 0.0;
    double maxX = 0.0;
    double maxY = 0.0;
};

class GpkgFeatureTable {
public:
    /// Looks `table` up in gpkg_geometry_columns (IoError when it is not a feature table) and
    /// drops its triggers, remembering their SQL.
    GpkgFeatureTable(SqliteConnection& connection, std::string table);

    [[nodiscard]] const std::string& table() const { return m_table; }
    [[nodiscard]] const std::string& geometryColumn() const { return m_geometryColumn; }
    /// The srs_id every geometry blob of the table carries.
    [[nodiscard]] std::int32_t srsId() const { return m_srsId; }

    /// Restores the triggers and records `features` rows covering `extent` (ignored when there
    /// are no features) in gpkg_contents and gpkg_ogr_contents.
    void finish(std::uint64_t features, const Extent2d& extent);

private:
    SqliteConnection* m_connection;
    std::string m_table;
    std::string m_geometryColumn;
    std::int32_t m_srsId = 0;
    std::vector<std::string> m_triggerSql;
};

} // namespace terratin::io::detail

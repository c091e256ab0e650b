#include "batched_insert.hpp"

namespace terratin::io::detail {

namespace {

std::string insertSql(const std::string& table, const std::vector<std::string>& columns, int rows) {
    std::string sql = "INSERT INTO " + quoteIdentifier(table) + " (";
    std::string oneRow = "(";
    for (std::size_t i = 0; i < columns.size(); ++i) {
        sql += (i == 0 ? "" : ", ") + quoteIdentifier(columns[i]);
        oneRow += i == 0 ? "?" : ", ?";
    }
    sql += ") VALUES ";
    oneRow += ")";
    for (int row = 0; row < rows; ++row)
        sql += (row == 0 ? "" : ", ") + oneRow;
    return sql;
}

} // namespace

BatchedInsert::BatchedInsert(SqliteConnection& connection, const std::string& table,
                             const std::vector<std::string>& columns)
    : m_columnCount(static_cast<int>(columns.size())),
      m_rowsPerStatement(
          std::clamp(connection.maxParameters() / m_columnCount, 1, kMaxRowsPerStatement)),
      m_manyRows(std::make_unique<SqliteStatement>(connection,
                                                   insertSql(table, columns, m_rowsPerStatement))),
      m_oneRow(std::make_unique<SqliteStatement>(connection, insertSql(table, columns, 1))) {}

} // namespace terratin::io::detail

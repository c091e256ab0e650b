#pragma once
/// @file
/// BatchedInsert: many rows into one table through one prepared statement that inserts
/// several rows at a time, "INSERT INTO t (...) VALUES (...), (...), ...".
///
/// Why several rows per statement: SQLite does fixed work per statement run besides the work
/// per row, and for a table keyed INTEGER PRIMARY KEY AUTOINCREMENT (every GeoPackage feature
/// table) that work includes rewriting the table's sqlite_sequence row. Measured figures are in
/// docs/benchmarks.md.

#include "sqlite_connection.hpp"

#include <algorithm>
#include <cstddef>
#include <memory>
#include <string>
#include <vector>

namespace terratin::io::detail {

class BatchedInsert {
public:
    /// Rows per statement at most; fewer when SQLite allows fewer parameters.
    static constexpr int kMaxRowsPerStatement = 64;

    BatchedInsert(SqliteConnection& connection, const std::string& table,
                  const std::vector<std::string>& columns);

    /// Inserts `rows` rows; bindRow(statement, firstParameter, row) binds the columns of row
    /// `row` (0-based) to parameters firstParameter, firstParameter + 1, ...
    template <class BindRow> void insert(std::size_t rows, BindRow&& bindRow) {
        std::size_t row = 0;
        const auto perStatement = static_cast<std::size_t>(m_rowsPerStatement);
        for (; rows - row >= perStatement; row += perStatement) {
            for (std::size_t i = 0; i < perStatement; ++i)
                bindRow(*m_manyRows, 1 + static_cast<int>(i) * m_columnCount, row + i);
            m_manyRows->run();
        }
        for (; row < rows; ++row) {
            bindRow(*m_oneRow, 1, row);
            m_oneRow->run();
        }
    }

private:
    int m_columnCount;
    int m_rowsPerStatement;
    std::unique_ptr<SqliteStatement> m_manyRows;
    std::unique_ptr<SqliteStatement> m_oneRow;
};

} // namespace terratin::io::detail

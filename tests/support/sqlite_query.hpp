#pragma once
// Plain SQLite queries on a written file, for tests that read what a writer put there.

#include <sqlite3.h>

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <string>

namespace terratin::test {

/// Runs one SQL query that returns one text value, with a plain SQLite connection.
inline std::string sqliteText(const std::filesystem::path& path, const std::string& sql) {
    sqlite3* db = nullptr;
    EXPECT_EQ(sqlite3_open_v2(path.c_str(), &db, SQLITE_OPEN_READONLY, nullptr), SQLITE_OK);
    sqlite3_stmt* statement = nullptr;
    std::string text = "<no row>";
    if (sqlite3_prepare_v2(db, sql.c_str(), -1, &statement, nullptr) != SQLITE_OK)
        text = std::string("<error: ") + sqlite3_errmsg(db) + ">";
    else if (sqlite3_step(statement) == SQLITE_ROW)
        text = reinterpret_cast<const char*>(sqlite3_column_text(statement, 0));
    sqlite3_finalize(statement);
    sqlite3_close(db);
    return text;
}

/// Every row the query returns, one line each, its values separated by '|' (blobs in hex).
inline std::string sqliteRows(const std::filesystem::path& path, const std::string& sql) {
    sqlite3* db = nullptr;
    EXPECT_EQ(sqlite3_open_v2(path.c_str(), &db, SQLITE_OPEN_READONLY, nullptr), SQLITE_OK);
    sqlite3_stmt* statement = nullptr;
    std::string rows;
    if (sqlite3_prepare_v2(db, sql.c_str(), -1, &statement, nullptr) != SQLITE_OK)
        rows = std::string("<error: ") + sqlite3_errmsg(db) + ">";
    while (statement != nullptr && sqlite3_step(statement) == SQLITE_ROW) {
        for (int c = 0; c < sqlite3_column_count(statement); ++c) {
            if (sqlite3_column_type(statement, c) == SQLITE_BLOB) {
                const auto* bytes =
                    static_cast<const unsigned char*>(sqlite3_column_blob(statement, c));
                for (int i = 0; i < sqlite3_column_bytes(statement, c); ++i) {
                    char hex[3];
                    std::snprintf(hex, sizeof hex, "%02x", bytes[i]);
                    rows += hex;
                }
            } else if (const unsigned char* text = sqlite3_column_text(statement, c)) {
                rows += reinterpret_cast<const char*>(text);
            }
            rows += '|';
        }
        rows += '\n';
    }
    sqlite3_finalize(statement);
    sqlite3_close(db);
    return rows;
}

inline std::string rtreeCheck(const std::filesystem::path& path, const std::string& layer) {
    return sqliteText(path, "SELECT rtreecheck('rtree_" + layer + "_geom')");
}

} // namespace terratin::test

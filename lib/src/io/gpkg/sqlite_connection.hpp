#pragma once
/// @file
/// SqliteConnection and SqliteStatement: the few SQLite calls the GeoPackage writer makes, with
/// every failure turned into IoError "<stage>: <what> in '<path>': <SQLite's message>".
///
/// This is the one place terratin talks to SQLite directly: to write rows and the R-tree into
/// a GeoPackage that OGR created (see gpkg_tin_writer.cpp for why), and to add layers to a
/// user's GeoPackage under SQLite's own locks and journal (gpkg_append.cpp).

#include <cstdint>
#include <exception>
#include <filesystem>
#include <functional>
#include <span>
#include <string>
#include <string_view>

struct sqlite3;
struct sqlite3_stmt;

namespace terratin::io::detail {

class SqliteConnection;

/// One prepared statement. Parameters are numbered from 1, as in SQLite.
class SqliteStatement {
public:
    SqliteStatement(SqliteConnection& connection, const std::string& sql);
    SqliteStatement(const SqliteStatement&) = delete;
    SqliteStatement& operator=(const SqliteStatement&) = delete;
    ~SqliteStatement();

    void bindInteger(int parameter, std::int64_t value);
    void bindReal(int parameter, double value);
    void bindNull(int parameter);
    /// The bytes are not copied: they must stay valid until the next step() returns.
    void bindBlob(int parameter, std::span<const std::uint8_t> bytes);
    void bindText(int parameter, std::string_view text);

    /// Runs the statement to completion (no result row expected) and resets it for new values.
    void run();
    /// Steps once: true while there is a result row to read with the column getters.
    bool nextRow();
    [[nodiscard]] std::int64_t integerColumn(int column) const;
    [[nodiscard]] std::string textColumn(int column) const;

private:
    SqliteConnection* m_connection;
    sqlite3_stmt* m_statement = nullptr;
};

/// An open database file.
class SqliteConnection {
public:
    /// Opens an existing file for writing. `stage` and `displayPath` make the error messages.
    SqliteConnection(std::string_view stage, const std::filesystem::path& path,
                     std::filesystem::path displayPath);
    SqliteConnection(const SqliteConnection&) = delete;
    SqliteConnection& operator=(const SqliteConnection&) = delete;
    ~SqliteConnection();

    /// Runs one or more statements that return no rows.
    void execute(const std::string& sql);
    /// The single integer a query such as "PRAGMA page_size" returns.
    [[nodiscard]] std::int64_t queryInteger(const std::string& sql);
    /// The most parameters one statement may have (SQLITE_LIMIT_VARIABLE_NUMBER).
    [[nodiscard]] int maxParameters() const;
    /// Closes the file, reporting a failure to flush it (which the destructor cannot).
    void close();

    /// Where another connection holds a lock this one needs, waits for it up to `limitSeconds`
    /// in all, calling `whileWaiting` every few milliseconds: when that throws (Cancelled, say)
    /// the wait ends and the statement's failure rethrows its exception. Past the limit the
    /// statement fails with a message saying that another program holds the file.
    void waitForLocks(double limitSeconds, std::function<void()> whileWaiting);
    /// Whether SQLite opened the file read-only (it does so, silently, when the file or its
    /// directory is not writable for this process).
    [[nodiscard]] bool isReadOnly() const;

    /// Throws IoError "<stage>: <what> in '<path>': <SQLite's last message>".
    [[noreturn]] void fail(std::string_view what) const;
    [[nodiscard]] sqlite3* handle() const { return m_database; }

private:
    /// SQLite's busy handler: `context` is the connection.
    static int onBusy(void* context, int attempt);

    std::string m_stage;
    std::filesystem::path m_displayPath;
    sqlite3* m_database = nullptr;
    double m_lockWaitLimitSeconds = 0.0;
    double m_lockWaitedSeconds = 0.0;
    std::function<void()> m_whileWaiting;
    /// What whileWaiting threw, rethrown by fail().
    std::exception_ptr m_waitError;
};

/// `name` as an SQL identifier: in double quotes, inner quotes doubled.
std::string quoteIdentifier(std::string_view name);
/// `text` as an SQL string literal: in single quotes, inner quotes doubled.
std::string quoteLiteral(std::string_view text);

} // namespace terratin::io::detail

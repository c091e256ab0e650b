#include "sqlite_connection.hpp"

#include "../atomic_output.hpp"
#include "terratin/error.hpp"

#include <sqlite3.h>

#include <cstdio>
#include <utility>

namespace terratin::io::detail {

namespace {

/// Milliseconds between two tries for a lock another connection holds: short enough that a
/// cancellation is seen at once, long enough that the wait costs no CPU to speak of.
constexpr int kLockPollMilliseconds = 25;

std::string quoteWith(std::string_view text, char quote) {
    std::string quoted(1, quote);
    for (const char ch : text) {
        quoted += ch;
        if (ch == quote)
            quoted += quote;
    }
    quoted += quote;
    return quoted;
}

} // namespace

std::string quoteIdentifier(std::string_view name) {
    return quoteWith(name, '"');
}

std::string quoteLiteral(std::string_view text) {
    return quoteWith(text, '\'');
}

SqliteConnection::SqliteConnection(std::string_view stage, const std::filesystem::path& path,
                                   std::filesystem::path displayPath)
    : m_stage(stage), m_displayPath(std::move(displayPath)) {
    // One thread at a time uses a connection (the writer's), so SQLite's lock around every
    // call, bind included, is not needed.
    const int status = sqlite3_open_v2(path.c_str(), &m_database,
                                       SQLITE_OPEN_READWRITE | SQLITE_OPEN_NOMUTEX, nullptr);
    if (status != SQLITE_OK) {
        const std::string message =
            m_database != nullptr ? sqlite3_errmsg(m_database) : sqlite3_errstr(status);
        sqlite3_close(m_database);
        m_database = nullptr;
        throw IoError(m_stage + ": cannot open " + quoted(m_displayPath) + ": " + message);
    }
    // Errors are reported with their SQLite message; extended codes tell disk full from others.
    sqlite3_extended_result_codes(m_database, 1);
}

SqliteConnection::~SqliteConnection() {
    if (m_database != nullptr)
        sqlite3_close_v2(m_database);
}

void SqliteConnection::execute(const std::string& sql) {
    if (sqlite3_exec(m_database, sql.c_str(), nullptr, nullptr, nullptr) != SQLITE_OK)
        fail("cannot write");
}

std::int64_t SqliteConnection::queryInteger(const std::string& sql) {
    SqliteStatement statement(*this, sql);
    if (!statement.nextRow())
        fail("no answer to '" + sql + "'");
    return statement.integerColumn(0);
}

int SqliteConnection::maxParameters() const {
    return sqlite3_limit(m_database, SQLITE_LIMIT_VARIABLE_NUMBER, -1);
}

void SqliteConnection::close() {
    if (m_database == nullptr)
        return;
    if (sqlite3_close(m_database) != SQLITE_OK)
        fail("cannot close");
    m_database = nullptr;
}

void SqliteConnection::waitForLocks(double limitSeconds, std::function<void()> whileWaiting) {
    m_lockWaitLimitSeconds = limitSeconds;
    m_whileWaiting = std::move(whileWaiting);
    sqlite3_busy_handler(m_database, &SqliteConnection::onBusy, this);
}

int SqliteConnection::onBusy(void* context, int /*attempt*/) {
    auto& connection = *static_cast<SqliteConnection*>(context);
    if (connection.m_waitError)
        return 0;
    try {
        if (connection.m_whileWaiting)
            connection.m_whileWaiting();
    } catch (...) {
        // SQLite is C: the exception waits here until the failing call reaches fail().
        connection.m_waitError = std::current_exception();
        return 0;
    }
    if (connection.m_lockWaitedSeconds >= connection.m_lockWaitLimitSeconds)
        return 0;
    sqlite3_sleep(kLockPollMilliseconds);
    connection.m_lockWaitedSeconds += kLockPollMilliseconds / 1000.0;
    return 1;
}

bool SqliteConnection::isReadOnly() const {
    return sqlite3_db_readonly(m_database, "main") == 1;
}

void SqliteConnection::fail(std::string_view what) const {
    if (m_waitError)
        std::rethrow_exception(m_waitError);
    const int code = m_database != nullptr ? sqlite3_extended_errcode(m_database) : SQLITE_OK;
    if ((code & 0xFF) == SQLITE_BUSY || (code & 0xFF) == SQLITE_LOCKED) {
        char waited[32];
        std::snprintf(waited, sizeof waited, "%.0f", m_lockWaitedSeconds);
        throw IoError(m_stage + ": " + std::string(what) + " in " + quoted(m_displayPath) +
                      ": another program holds a lock on it (waited " + waited +
                      " s); try again when it has finished");
    }
    throw IoError(m_stage + ": " + std::string(what) + " in " + quoted(m_displayPath) + ": " +
                  (m_database != nullptr ? sqlite3_errmsg(m_database) : "no database"));
}

SqliteStatement::SqliteStatement(SqliteConnection& connection, const std::string& sql)
    : m_connection(&connection) {
    if (sqlite3_prepare_v2(connection.handle(), sql.c_str(), static_cast<int>(sql.size()),
                           &m_statement, nullptr) != SQLITE_OK)
        connection.fail("cannot prepare a statement");
}

SqliteStatement::~SqliteStatement() {
    sqlite3_finalize(m_statement);
}

void SqliteStatement::bindInteger(int parameter, std::int64_t value) {
    if (sqlite3_bind_int64(m_statement, parameter, value) != SQLITE_OK)
        m_connection->fail("cannot bind a value");
}

void SqliteStatement::bindReal(int parameter, double value) {
    if (sqlite3_bind_double(m_statement, parameter, value) != SQLITE_OK)
        m_connection->fail("cannot bind a value");
}

void SqliteStatement::bindNull(int parameter) {
    if (sqlite3_bind_null(m_statement, parameter) != SQLITE_OK)
        m_connection->fail("cannot bind a value");
}

void SqliteStatement::bindBlob(int parameter, std::span<const std::uint8_t> bytes) {
    if (sqlite3_bind_blob(m_statement, parameter, bytes.data(), static_cast<int>(bytes.size()),
                          SQLITE_STATIC) != SQLITE_OK)
        m_connection->fail("cannot bind a value");
}

void SqliteStatement::bindText(int parameter, std::string_view text) {
    if (sqlite3_bind_text(m_statement, parameter, text.data(), static_cast<int>(text.size()),
                          SQLITE_TRANSIENT) != SQLITE_OK)
        m_connection->fail("cannot bind a value");
}

void SqliteStatement::run() {
    const int status = sqlite3_step(m_statement);
    if (status != SQLITE_DONE && status != SQLITE_ROW)
        m_connection->fail("cannot write");
    sqlite3_reset(m_statement);
}

bool SqliteStatement::nextRow() {
    const int status = sqlite3_step(m_statement);
    if (status == SQLITE_ROW)
        return true;
    if (status != SQLITE_DONE)
        m_connection->fail("cannot read");
    return false;
}

std::int64_t SqliteStatement::integerColumn(int column) const {
    return sqlite3_column_int64(m_statement, column);
}

std::string SqliteStatement::textColumn(int column) const {
    const auto* text = reinterpret_cast<const char*>(sqlite3_column_text(m_statement, column));
    return text != nullptr ? std::string(text) : std::string();
}

} // namespace terratin::io::detail

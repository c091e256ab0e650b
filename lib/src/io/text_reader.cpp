/// @file
/// TextReader: delimited text to points.
///
/// The file is read in 4 MiB chunks; complete lines are parsed in place from the chunk and the
/// unfinished last line is moved to the front before the next read, so no line is copied
/// except the one straddling a chunk boundary. Numbers go through std::from_chars (exact
/// round-to-nearest conversion, no locale, no allocation).

#include "terratin/io/text_reader.hpp"

#include "../text.hpp"
#include "terratin/error.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace terratin::io {

using terratin::detail::lowercase;

namespace {

constexpr std::string_view kStage = "TextReader";
constexpr std::size_t kChunkBytes = std::size_t{4} << 20;
/// A longer line is not a point record; refusing it bounds the buffer.
constexpr std::size_t kMaxLineBytes = std::size_t{1} << 20;
/// The UTF-8 encoding of U+FEFF, skipped at the start of the first line.
constexpr std::string_view kUtf8Bom = "\xEF\xBB\xBF";
/// More columns than this in --columns is a mistake, not a file layout.
constexpr std::size_t kMaxColumnNumber = 10000;

bool isBlank(char c) {
    return c == ' ' || c == '\t';
}

std::string_view trim(std::string_view text) {
    while (!text.empty() && isBlank(text.front()))
        text.remove_prefix(1);
    while (!text.empty() && isBlank(text.back()))
        text.remove_suffix(1);
    if (text.size() >= 2 && text.front() == '"' && text.back() == '"')
        text = text.substr(1, text.size() - 2);
    return text;
}

/// Parses a whole field as a finite double; false when it is not one.
/// A number from_chars found out of range: finite when its magnitude is below the smallest
/// double (1e-999 is 0 to a double, as strtod rounds it), not when it is above the largest.
bool parseUnderflow(std::string_view field, double& value) {
    const std::string text(field);
    char* end = nullptr;
    errno = 0;
    const double rounded = std::strtod(text.c_str(), &end);
    if (end != text.c_str() + text.size() || errno != ERANGE ||
        !(std::fabs(rounded) <= std::numeric_limits<double>::min()))
        return false;
    value = rounded;
    return true;
}

bool parseNumber(std::string_view field, double& value) {
    if (!field.empty() && field.front() == '+')
        field.remove_prefix(1);
    if (field.empty())
        return false;
    const char* end = field.data() + field.size();
    const auto [ptr, error] = std::from_chars(field.data(), end, value);
    if (error == std::errc::result_out_of_range && ptr == end)
        return parseUnderflow(field, value);
    return error == std::errc() && ptr == end && std::isfinite(value);
}

/// Whether a field reads as a number, finite or not (a header's names do not).
bool looksNumeric(std::string_view field) {
    double ignored = 0.0;
    if (!field.empty() && field.front() == '+')
        field.remove_prefix(1);
    const char* end = field.data() + field.size();
    const auto [ptr, error] = std::from_chars(field.data(), end, ignored);
    return !field.empty() && ptr == end &&
           (error == std::errc() || error == std::errc::result_out_of_range);
}

/// The column of the lower-case header `names` called `wanted`, case-insensitively.
std::optional<std::size_t> findName(const std::vector<std::string>& names,
                                    std::string_view wanted) {
    const std::string key = lowercase(wanted);
    for (std::size_t i = 0; i < names.size(); ++i)
        if (names[i] == key)
            return i;
    return std::nullopt;
}

/// Turns lines into points; configured by the first meaningful line.
class LineParser {
public:
    LineParser(std::string name, const TextReadOptions& options, PointCloud& cloud)
        : m_name(std::move(name)), m_options(options), m_cloud(cloud) {
        if (options.delimiter) {
            const char d = *options.delimiter;
            if (d != ' ' && d != '\t' && d != ',' && d != ';' && d != '|')
                throw InvalidInputError(std::string(kStage) + ": the delimiter must be space, "
                                                              "tab, ',', ';' or '|'");
            m_delimiter = d == '\t' ? ' ' : d;
        }
        if (!options.columns.empty() && options.columns.size() != 3)
            throw InvalidInputError(std::string(kStage) + ": " + markOption("columns") +
                                    " takes three columns (x,y,z), got " +
                                    std::to_string(options.columns.size()));
    }

    void line(std::string_view text, std::uint64_t number) {
        if (!text.empty() && text.back() == '\r')
            text.remove_suffix(1);
        // A UTF-8 byte order mark, which Windows editors put at the start of a file.
        if (number == 1 && text.substr(0, kUtf8Bom.size()) == kUtf8Bom)
            text.remove_prefix(kUtf8Bom.size());
        std::size_t start = 0;
        while (start < text.size() && isBlank(text[start]))
            ++start;
        if (start == text.size() || text[start] == '#')
            return;
        if (!m_configured) {
            configure(text, number);
            if (m_headerSeen)
                return;
        }
        dataLine(text, number);
    }

    void finish() const {
        if (m_cloud.points.empty())
            throw InvalidInputError(std::string(kStage) + ": '" + m_name +
                                    "' holds no point (no line of x, y, z numbers)");
    }

private:
    /// Splits `text` into at most `limit` fields; returns how many it found.
    std::size_t split(std::string_view text, std::size_t limit) {
        std::size_t count = 0;
        std::size_t pos = 0;
        const std::size_t size = text.size();
        if (m_delimiter == ' ') {
            while (count < limit) {
                while (pos < size && isBlank(text[pos]))
                    ++pos;
                if (pos == size)
                    break;
                const std::size_t begin = pos;
                while (pos < size && !isBlank(text[pos]))
                    ++pos;
                m_fields[count++] = trim(text.substr(begin, pos - begin));
            }
            return count;
        }
        while (count < limit) {
            const std::size_t end = text.find(*m_delimiter, pos);
            const std::size_t stop = end == std::string_view::npos ? size : end;
            m_fields[count++] = trim(text.substr(pos, stop - pos));
            if (end == std::string_view::npos)
                break;
            pos = end + 1;
        }
        return count;
    }

    std::string columnsName() const { return markOption("columns"); }

    std::string where(std::uint64_t number) const {
        return std::string(kStage) + ": '" + m_name + "' line " + std::to_string(number) + ": ";
    }

    /// The first meaningful line: the delimiter (unless given), whether the line is a header,
    /// and the columns of x, y and z.
    void configure(std::string_view text, std::uint64_t number) {
        m_configured = true;
        if (!m_delimiter)
            m_delimiter = guessDelimiter(text);
        const std::vector<std::string_view> all = allFields(text);
        const ColumnRequest request = requestedColumns();
        const bool header = isHeader(all, request, number);
        std::vector<std::string> names;
        if (header) {
            m_headerSeen = true;
            for (const std::string_view field : all)
                names.push_back(lowercase(field));
        }
        if (!m_options.columns.empty())
            m_columns = requestedIndices(request, names, header, number);
        else
            m_columns = header ? columnsNamed(names) : std::array<std::size_t, 3>{0, 1, 2};
        m_needed = std::max({m_columns[0], m_columns[1], m_columns[2]}) + 1;
        m_fields.resize(m_needed);
    }

    /// '|', ';' or ',' when the line holds one (in that order), else blanks.
    static char guessDelimiter(std::string_view text) {
        for (const char candidate : {'|', ';', ','})
            if (text.find(candidate) != std::string_view::npos)
                return candidate;
        return ' ';
    }

    /// Every field of the line.
    std::vector<std::string_view> allFields(std::string_view text) {
        // A line of n bytes has at most n + 1 fields.
        const std::size_t limit = std::min(kMaxColumnNumber, text.size() + 1);
        m_fields.resize(limit);
        const std::size_t count = split(text, limit);
        return {m_fields.begin(), m_fields.begin() + static_cast<std::ptrdiff_t>(count)};
    }

    /// The columns --columns asks for: by number (from 0) where given as one, else by name.
    struct ColumnRequest {
        std::array<std::optional<std::size_t>, 3> byNumber;
        bool namesGiven = false;
    };

    [[nodiscard]] ColumnRequest requestedColumns() const {
        ColumnRequest request;
        for (std::size_t i = 0; i < m_options.columns.size(); ++i) {
            const std::string_view entry = trim(m_options.columns[i]);
            if (entry.empty())
                throw InvalidInputError(std::string(kStage) + ": empty entry in " + columnsName());
            if (!std::all_of(entry.begin(), entry.end(),
                             [](char c) { return c >= '0' && c <= '9'; })) {
                request.namesGiven = true;
                continue;
            }
            std::size_t value = 0;
            const auto [ptr, error] =
                std::from_chars(entry.data(), entry.data() + entry.size(), value);
            if (error != std::errc() || value == 0 || value > kMaxColumnNumber)
                throw InvalidInputError(std::string(kStage) + ": column '" + std::string(entry) +
                                        "' in " + columnsName() +
                                        ": columns are numbered from 1 to " +
                                        std::to_string(kMaxColumnNumber));
            request.byNumber[i] = value - 1;
        }
        return request;
    }

    /// A header: a named column was asked for, or none of the chosen columns of this line
    /// reads as a number (a line with some numbers is data, to be reported if bad).
    [[nodiscard]] bool isHeader(const std::vector<std::string_view>& all,
                                const ColumnRequest& request, std::uint64_t number) const {
        bool header = true;
        for (std::size_t i = 0; i < 3; ++i) {
            const std::size_t index = request.byNumber[i].value_or(i);
            if (index < all.size() && looksNumeric(all[index]))
                header = false;
        }
        if (!request.namesGiven)
            return header;
        if (std::all_of(all.begin(), all.end(), looksNumeric))
            throw InvalidInputError(where(number) + "no header line to find the columns named in " +
                                    columnsName() + " (the first line is numbers)");
        return true;
    }

    /// The columns --columns asks for, the named ones found in the header's `names`.
    [[nodiscard]] std::array<std::size_t, 3> requestedIndices(const ColumnRequest& request,
                                                              const std::vector<std::string>& names,
                                                              bool header,
                                                              std::uint64_t number) const {
        std::array<std::size_t, 3> columns{};
        for (std::size_t i = 0; i < 3; ++i) {
            if (request.byNumber[i]) {
                columns[i] = *request.byNumber[i];
                continue;
            }
            const std::string_view entry = trim(m_options.columns[i]);
            if (!header)
                throw InvalidInputError(where(number) + "no header line to find column '" +
                                        std::string(entry) + "' of " + columnsName() + " in");
            const auto found = findName(names, entry);
            if (!found)
                throw InvalidInputError(where(number) + "the header has no column '" +
                                        std::string(entry) + "'");
            columns[i] = *found;
        }
        return columns;
    }

    /// The columns of a header whose names say x, y and z (x / easting / lon..., in that order
    /// of preference); the first three when one of them is missing.
    static std::array<std::size_t, 3> columnsNamed(const std::vector<std::string>& names) {
        static constexpr std::array<std::array<std::string_view, 7>, 3> kNames{{
            {"x", "easting", "east", "lon", "long", "longitude", "e"},
            {"y", "northing", "north", "lat", "latitude", "n", "nord"},
            {"z", "elevation", "elev", "height", "alt", "altitude", "h"},
        }};
        std::array<std::optional<std::size_t>, 3> found;
        for (std::size_t axis = 0; axis < 3; ++axis)
            for (const std::string_view candidate : kNames[axis])
                if (!found[axis])
                    found[axis] = findName(names, candidate);
        if (found[0] && found[1] && found[2])
            return {*found[0], *found[1], *found[2]};
        return {0, 1, 2};
    }

    void dataLine(std::string_view text, std::uint64_t number) {
        ++m_cloud.recordsRead;
        const std::size_t count = split(text, m_needed);
        if (count < m_needed)
            throw InvalidInputError(where(number) + "has " + std::to_string(count) +
                                    " column(s); column " + std::to_string(m_needed) +
                                    " is needed");
        std::array<double, 3> xyz{};
        for (std::size_t axis = 0; axis < 3; ++axis) {
            const std::string_view field = m_fields[m_columns[axis]];
            if (!parseNumber(field, xyz[axis]))
                throw InvalidInputError(
                    where(number) + "column " + std::to_string(m_columns[axis] + 1) + " ('" +
                    std::string(field.substr(0, 40)) + "') is not a finite number");
        }
        m_cloud.points.push_back({xyz[0], xyz[1], xyz[2]});
    }

    std::string m_name;
    const TextReadOptions& m_options;
    PointCloud& m_cloud;
    bool m_configured = false;
    bool m_headerSeen = false;
    std::optional<char> m_delimiter;
    std::array<std::size_t, 3> m_columns{0, 1, 2};
    std::size_t m_needed = 3;
    std::vector<std::string_view> m_fields;
};

/// Feeds the complete lines of `data` to `parser`; returns the bytes consumed (up to and
/// including the last newline, or everything when `final`).
std::size_t parseLines(std::string_view data, bool final, LineParser& parser,
                       std::uint64_t& lineNumber, const std::string& name) {
    if (std::memchr(data.data(), '\0', data.size()) != nullptr)
        throw InvalidInputError(std::string(kStage) + ": '" + name +
                                "' is not a text file (it holds NUL bytes)");
    std::size_t pos = 0;
    while (pos < data.size()) {
        const void* found = std::memchr(data.data() + pos, '\n', data.size() - pos);
        if (found == nullptr) {
            if (!final)
                break;
            if (data.size() - pos > kMaxLineBytes)
                throw InvalidInputError(std::string(kStage) + ": '" + name + "' line " +
                                        std::to_string(lineNumber + 1) + " is longer than 1 MiB");
            parser.line(data.substr(pos), ++lineNumber);
            return data.size();
        }
        const auto end = static_cast<std::size_t>(static_cast<const char*>(found) - data.data());
        if (end - pos > kMaxLineBytes)
            throw InvalidInputError(std::string(kStage) + ": '" + name + "' line " +
                                    std::to_string(lineNumber + 1) + " is longer than 1 MiB");
        parser.line(data.substr(pos, end - pos), ++lineNumber);
        pos = end + 1;
    }
    if (!final && data.size() - pos > kMaxLineBytes)
        throw InvalidInputError(std::string(kStage) + ": '" + name + "' line " +
                                std::to_string(lineNumber + 1) + " is longer than 1 MiB");
    return pos;
}

struct FileCloser {
    void operator()(std::FILE* file) const { std::fclose(file); }
};

} // namespace

PointCloud readTextPoints(const std::string& path, const TextReadOptions& options,
                          const ProgressCallback& progress) {
    const std::unique_ptr<std::FILE, FileCloser> file(std::fopen(path.c_str(), "rb"));
    if (!file)
        throw IoError(std::string(kStage) + ": cannot open '" + path +
                      "': " + std::strerror(errno));
    std::uint64_t fileSize = 0;
    if (fseeko(file.get(), 0, SEEK_END) == 0) {
        const off_t end = ftello(file.get());
        fileSize = end > 0 ? static_cast<std::uint64_t>(end) : 0;
        if (fseeko(file.get(), 0, SEEK_SET) != 0)
            throw IoError(std::string(kStage) + ": cannot seek in '" + path + "'");
    }

    PointCloud cloud;
    cloud.path = path;
    cloud.kind = InputKind::Text;
    // A point line is rarely under 16 bytes: reserving size / 32 avoids most reallocations
    // without overcommitting for wide lines.
    cloud.points.reserve(
        static_cast<std::size_t>(std::min<std::uint64_t>(fileSize / 32, std::uint64_t{1} << 28)));
    LineParser parser(path, options, cloud);
    // Room for a chunk plus a carried-over partial line.
    std::vector<char> buffer(kChunkBytes + kMaxLineBytes + 1);
    std::size_t held = 0;
    std::uint64_t lineNumber = 0;
    std::uint64_t bytesRead = 0;
    for (;;) {
        const std::size_t got = std::fread(buffer.data() + held, 1, kChunkBytes, file.get());
        if (got < kChunkBytes && std::ferror(file.get()))
            throw IoError(std::string(kStage) + ": cannot read '" + path + "'");
        bytesRead += got;
        held += got;
        const bool final = got == 0 || std::feof(file.get());
        const std::size_t used =
            parseLines(std::string_view(buffer.data(), held), final, parser, lineNumber, path);
        std::memmove(buffer.data(), buffer.data() + used, held - used);
        held -= used;
        if (progress && fileSize > 0 &&
            !progress(std::min(1.0, static_cast<double>(bytesRead) / static_cast<double>(fileSize)),
                      "reading text"))
            throw Cancelled(std::string(kStage) + ": cancelled while reading '" + path + "'");
        if (final)
            break;
    }
    parser.finish();
    return cloud;
}

PointCloud readTextPointsFromMemory(std::string_view text, const std::string& name,
                                    const TextReadOptions& options) {
    PointCloud cloud;
    cloud.path = name;
    cloud.kind = InputKind::Text;
    LineParser parser(name, options, cloud);
    std::uint64_t lineNumber = 0;
    parseLines(text, true, parser, lineNumber, name);
    parser.finish();
    return cloud;
}

} // namespace terratin::io

#pragma once
/// @file
/// The one error hierarchy of terratin. Every failure is thrown as a terratin::Error (never a
/// silent empty result); the message starts with the stage that failed ("GdalRasterReader: ...")
/// so that a single stderr line tells the user what went wrong and where.

#include <functional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace terratin {

/// `text` on one line: each run of line breaks and tabs, with the spaces around it, becomes one
/// space (nothing at either end of the text). GDAL and PROJ messages, and file names, may hold
/// newlines; a message that stays on one line is what a script reading stderr relies on.
inline std::string oneLine(std::string_view text) {
    std::string line;
    line.reserve(text.size());
    bool inBreak = false;
    for (const char c : text) {
        if (c == '\n' || c == '\r' || c == '\t') {
            inBreak = true;
        } else if (inBreak && c == ' ') {
            continue;
        } else {
            if (inBreak) {
                while (!line.empty() && line.back() == ' ')
                    line.pop_back();
                if (!line.empty())
                    line += ' ';
                inBreak = false;
            }
            line += c;
        }
    }
    if (inBreak)
        while (!line.empty() && line.back() == ' ')
            line.pop_back();
    return line;
}

/// A build option named in a message, by its keyword ("overwrite", "z_field"): the message
/// carries the keyword as data, between two marks no text holds, and the caller that shows the
/// message names the option its own way (Error::nameOptions): the command line says
/// `--overwrite`, a keyword caller (C++, Python) `overwrite`. So a module below the option table
/// names an option without knowing how it is spelled.
inline std::string markOption(std::string_view keyword) {
    // Appended piecewise: GCC 12 warns a spurious -Wrestrict on "\x1e" + string + "\x1f".
    std::string marked(1, '\x1e');
    marked += keyword;
    marked += '\x1f';
    return marked;
}

/// How a caller names the option of a keyword; an empty one names it by the keyword itself.
using OptionNaming = std::function<std::string(std::string_view keyword)>;

/// `text` with each option markOption marked named as `naming` names it.
inline std::string nameMarkedOptions(std::string_view text, const OptionNaming& naming = {}) {
    std::string named;
    named.reserve(text.size());
    std::size_t at = 0;
    while (at < text.size()) {
        const std::size_t open = text.find('\x1e', at);
        const std::size_t close = open == std::string_view::npos ? open : text.find('\x1f', open);
        if (close == std::string_view::npos) {
            named += text.substr(at);
            break;
        }
        const std::string_view keyword = text.substr(open + 1, close - open - 1);
        named += text.substr(at, open - at);
        named += naming ? naming(keyword) : std::string(keyword);
        at = close + 1;
    }
    return named;
}

/// The keywords of the options markOption marked in `text`, in order.
inline std::vector<std::string> markedOptions(std::string_view text) {
    std::vector<std::string> keywords;
    for (std::size_t open = text.find('\x1e'); open != std::string_view::npos;
         open = text.find('\x1e', open + 1)) {
        const std::size_t close = text.find('\x1f', open);
        if (close == std::string_view::npos)
            break;
        keywords.emplace_back(text.substr(open + 1, close - open - 1));
    }
    return keywords;
}

/// Base of every error terratin throws. The message is kept on one line (oneLine); the options
/// it names (markOption) are named by their keywords until a caller names them its way.
class Error : public std::runtime_error {
public:
    explicit Error(const std::string& message)
        : std::runtime_error(std::string()), m_marked(oneLine(message)),
          m_shown(nameMarkedOptions(m_marked)) {}
    explicit Error(const char* message) : Error(std::string(message)) {}

    const char* what() const noexcept override { return m_shown.c_str(); }
    /// The message with its options still marked, for a message that wraps this one.
    const std::string& markedMessage() const noexcept { return m_marked; }
    /// The keywords of the options the message names.
    std::vector<std::string> options() const { return markedOptions(m_marked); }
    /// Names the message's options as `naming` does, from now on (what()).
    void nameOptions(const OptionNaming& naming) { m_shown = nameMarkedOptions(m_marked, naming); }

private:
    std::string m_marked;
    std::string m_shown;
};

/// A file could not be opened, read, written or renamed.
class IoError : public Error {
public:
    using Error::Error;
};

/// The input is readable but unusable: too few points, all nodata, a band that does not exist...
class InvalidInputError : public Error {
public:
    using Error::Error;
};

/// A coordinate reference system is missing, unknown or cannot be transformed.
class CrsError : public Error {
public:
    using Error::Error;
};

/// The progress callback asked to stop (Ctrl-C in the CLI).
class Cancelled : public Error {
public:
    using Error::Error;
};

} // namespace terratin

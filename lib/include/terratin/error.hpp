#pragma once
/// @file
/// The one error hierarchy of terratin. Every failure is thrown as a terratin::Error (never a
/// silent empty result); the message starts with the stage that failed ("GdalRasterReader: ...")
/// so that a single stderr line tells the user what went wrong and where.

#include <stdexcept>
#include <string>
#include <string_view>

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

/// Base of every error terratin throws. The message is kept on one line (oneLine).
class Error : public std::runtime_error {
public:
    explicit Error(const std::string& message) : std::runtime_error(oneLine(message)) {}
    explicit Error(const char* message) : std::runtime_error(oneLine(message)) {}
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

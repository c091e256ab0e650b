#pragma once
/// @file
/// The one error hierarchy of terratin. Every failure is thrown as a terratin::Error (never a
/// silent empty result); the message starts with the stage that failed ("GdalRasterReader: ...")
/// so that a single stderr line tells the user what went wrong and where.

#include <stdexcept>
#include <string>

namespace terratin {

/// Base of every error terratin throws.
class Error : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
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

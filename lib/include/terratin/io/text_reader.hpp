#pragma once
/// @file
/// TextReader: delimited text point files (x y z per line: .xyz, .txt, .csv...). No GDAL: the
/// parser is plain C++ (std::from_chars on large buffered reads), so that it can be fuzzed and
/// is fast (terratin-readbench measures it; docs/benchmarks.md).

#include "terratin/io/point_source.hpp"
#include "terratin/progress.hpp"

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace terratin::io {

/// How to read a delimited text file.
struct TextReadOptions {
    /// The x, y and z columns: each a 1-based column number ("1") or a name from the header
    /// line ("easting"). Empty: x, y, z (or easting / lon..., northing / lat..., elevation /
    /// height...) by name when the header has all three, else columns 1, 2, 3.
    std::vector<std::string> columns;
    /// The field separator: one of ' ' (runs of spaces and tabs), ',', ';', '|', '\t'. Unset:
    /// decided from the first non-comment line ('|', else ';', else ',', else whitespace).
    std::optional<char> delimiter;
};

/// Reads the points of a delimited text file, one per line.
///
/// Lines are separated by LF or CRLF; empty lines and lines starting with '#' are skipped. The
/// first other line is a header when one of the chosen columns does not parse as a number
/// (or when `columns` names a column). Numbers are C-locale decimals ("1.5e3", no thousands
/// separators); a field may be surrounded by spaces and double quotes. The file has no CRS
/// (PointCloud::crsWkt is empty); recordsRead counts the data lines.
/// Throws IoError when the file cannot be opened or read; InvalidInputError naming the line
/// for a missing column, a field that is not a finite number, a line over 1 MiB, binary
/// content (a NUL byte), a bad `columns` entry, or a file without any data line;
/// Cancelled when `progress` returns false.
/// Complexity: O(bytes); 24 bytes per point and a 4 MiB read buffer.
PointCloud readTextPoints(const std::string& path, const TextReadOptions& options = {},
                          const ProgressCallback& progress = {});

/// The same, from text held in memory; `name` appears in messages and PointCloud::path.
PointCloud readTextPointsFromMemory(std::string_view text, const std::string& name,
                                    const TextReadOptions& options = {});

} // namespace terratin::io

#pragma once
/// @file
/// OgrTinWriter: a TinMesh as Polygon Z features through OGR, in a GeoPackage, an ESRI
/// Shapefile or a FlatGeobuf, with optional GeoPackage node and edge layers.

#include "atomic_output.hpp"
#include "terratin/io/tin_writer.hpp"

#include <cstddef>
#include <filesystem>

namespace terratin::io::detail {

/// InvalidInputError unless a Shapefile's `output` ends in .shp (in any case).
void checkShapefileName(const std::filesystem::path& output);

/// Creates the directory, under a temporary name of `temporaries`, that a Shapefile is written
/// in, and returns the path of its .shp there: the output's stem, a lower-case extension.
/// Throws IoError.
std::filesystem::path makeShapefileDirectory(const AtomicOutput& temporaries,
                                             const std::filesystem::path& output);

/// Renames every component written next to `temporaryShp` onto the output's (each in the case
/// of the output's extension), the .shp last, as one commitAll of `temporaries`; with
/// `overwrite`, then removes the replaced Shapefile's sidecars that were not rewritten.
void commitShapefile(const AtomicOutput& temporaries, const std::filesystem::path& temporaryShp,
                     const std::filesystem::path& output, bool overwrite);

/// The files that count as "the output exists" for `format`: for a Shapefile every component
/// and sidecar (.shx .dbf .prj .cpg .qix .sbn .sbx .qml ...), in lower and upper case.
std::vector<std::filesystem::path> ogrOutputFiles(const std::filesystem::path& output,
                                                  TinFormat format);

/// Writes everything (preconditions checked by writeTin: valid mesh, options, location).
/// Returns the features written over all layers.
TinWriteResult writeOgrTin(const TinMesh& mesh, const std::filesystem::path& output,
                           const TinWriteOptions& options, const ProgressCallback& progress);

} // namespace terratin::io::detail

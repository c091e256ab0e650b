#pragma once
/// @file
/// OgrTinWriter: a TinMesh as Polygon Z features through OGR, in a GeoPackage, an ESRI
/// Shapefile or a FlatGeobuf, with optional GeoPackage node and edge layers.

#include "terratin/io/tin_writer.hpp"

#include <cstddef>
#include <filesystem>

namespace terratin::io::detail {

/// Refuses (InvalidInputError naming GeoPackage as the way out) a Shapefile whose .shp or
/// .dbf would pass the format's 2 GB limit. The sizes are exact: every record has the same
/// size (one 4-point PolygonZ ring; fixed-width numeric columns).
void checkShapefileLimits(std::size_t triangleCount, AttributeSet attributes,
                          const std::filesystem::path& output);

/// The files that count as "the output exists" for `format`: for a Shapefile every component
/// and sidecar (.shx .dbf .prj .cpg .qix .sbn .sbx .qml ...), in lower and upper case.
std::vector<std::filesystem::path> ogrOutputFiles(const std::filesystem::path& output,
                                                  TinFormat format);

/// Writes everything (preconditions checked by writeTin: valid mesh, options, location).
/// Returns the features written over all layers.
TinWriteResult writeOgrTin(const TinMesh& mesh, const std::filesystem::path& output,
                           const TinWriteOptions& options, const ProgressCallback& progress);

} // namespace terratin::io::detail

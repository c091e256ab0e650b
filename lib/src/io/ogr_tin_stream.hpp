#pragma once
/// @file
/// The Shapefile and FlatGeobuf TinStreamWriter: OGR creates the file and its triangle layer
/// as ogr_tin_writer does and keeps it open, and each piece's triangles go in as they come.
/// A Shapefile holds nothing back but one triangle (its last goes in with the DBF end mark);
/// a FlatGeobuf with a spatial index keeps GDAL's index entry of every feature until the
/// file is closed, when GDAL sorts and copies the features from its temporary file.

#include "tin_stream.hpp"

#include <filesystem>
#include <memory>

namespace terratin::io::detail {

/// Preconditions are checked by openTinStream.
std::unique_ptr<TinStreamWriter> openOgrTinStream(const std::filesystem::path& output,
                                                  const TinWriteOptions& options);

} // namespace terratin::io::detail

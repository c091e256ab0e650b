#pragma once
/// @file
/// The GeoPackage TinStreamWriter: OGR creates the file and its layers as gpkg_tin_writer
/// does, each piece's rows go in as it comes (feature ids continuing), and the spatial
/// indexes are packed at the end from the boxes kept: 16 bytes a feature, the only part of
/// the TIN held.

#include "../tin_stream.hpp"

#include <filesystem>
#include <memory>

namespace terratin::io::detail {

/// Preconditions are checked by openTinStream.
std::unique_ptr<TinStreamWriter> openGpkgTinStream(const std::filesystem::path& output,
                                                   const TinWriteOptions& options);

} // namespace terratin::io::detail

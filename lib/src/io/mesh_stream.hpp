#pragma once
/// @file
/// The mesh formats' TinStreamWriter (PLY, 2DM, OBJ, LandXML): each piece's vertex and face
/// records go to two temporaries beside the output as they come, and finish() writes the file
/// from them under the head, which needs what only the whole TIN gives (PLY's counts,
/// LandXML's areas and elevation range, OBJ's local origin: its vertices are kept as raw
/// doubles and written out then). The file is the one writeTin writes of the whole TIN.

#include "tin_stream.hpp"

#include <filesystem>
#include <memory>

namespace terratin::io::detail {

/// Preconditions are checked by openTinStream.
std::unique_ptr<TinStreamWriter> openMeshTinStream(const std::filesystem::path& output,
                                                   const TinWriteOptions& options);

} // namespace terratin::io::detail

#pragma once
/// @file
/// The index of a directory of tiles (`terratin build --tiles-dir`): a GeoPackage
/// layer "tiles" with one polygon per tile written, its footprint, and where its TIN is.

#include <array>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace terratin::io {

/// One tile's row of the index.
struct TileIndexEntry {
    /// The tile's file name, relative to the index's directory.
    std::string file;
    std::int64_t tileRow = 0;
    std::int64_t tileColumn = 0;
    std::int64_t points = 0;
    std::int64_t triangles = 0;
    /// The footprint's corners (x, y), counter-clockwise: the rectangle through the centres of
    /// the tile's corner cells, which its TIN covers where it has data.
    std::array<std::array<double, 2>, 4> corners{};
};

/// Writes `entries` as the GeoPackage `path` (layer "tiles", CRS `crsWkt`, none when empty),
/// under a temporary name renamed into place when complete. Throws IoError, CrsError, and
/// InvalidInputError when `path` exists and `overwrite` is false (the option marked,
/// markOption).
void writeTileIndex(const std::filesystem::path& path, const std::string& crsWkt,
                    const std::vector<TileIndexEntry>& entries, bool overwrite);

} // namespace terratin::io

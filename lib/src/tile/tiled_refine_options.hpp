#pragma once
/// @file
/// The options of one tiled refinement as the tiles' code reads them: the refiner's and the
/// tiles' together (options.maxError, options.tileSize), each tile's own refinement taking the
/// refiner's part alone.

#include "terratin/refine/refine.hpp"
#include "terratin/tile/refine_tiles.hpp"

namespace terratin::detail {

struct TiledRefineOptions : RefineOptions, TileOptions {
    TiledRefineOptions() = default;
    TiledRefineOptions(const RefineOptions& refine, const TileOptions& tiles)
        : RefineOptions(refine), TileOptions(tiles) {}
};

} // namespace terratin::detail

#pragma once
/// @file
/// The producers of runBuild, one per kind of build; each takes a BuildRun whose options are
/// checked and planned (runBuild), reads its inputs, makes its TIN and hands it to the run's
/// sink. Throws as runBuild does.

#include "build_run.hpp"

#include "terratin/tile/refine_tiles.hpp"

namespace terratin::detail {

/// Point clouds, or rasters at full resolution: every point a vertex, exactly Delaunay (and
/// constrained, with breaklines or areas).
BuildReport buildPointTin(BuildRun& run);

/// A DEM simplified (options.refine), whole or in tiles (options.tileSize or memoryLimit),
/// with constraints when whole.
BuildReport buildRefinedTin(BuildRun& run);

/// The tiles of a DEM's tiled build as far as the options alone say: their size (0 while
/// memoryLimit has still to size them), every cell a vertex without a maximum error or a
/// limit, the processes sharing them. Needs options.refine.
TileOptions tileOptionsOf(const BuildOptions& options);

/// What the simplified and tiled builds refuse of the options alone (a usage error, found
/// before anything is read): InvalidInputError. Needs options.refine.
void checkDemOnlyOptions(const BuildOptions& options);

} // namespace terratin::detail

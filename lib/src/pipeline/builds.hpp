#pragma once
/// @file
/// The producers of runBuild, one per kind of build; each takes a BuildRun whose options are
/// checked and planned (runBuild), reads its inputs, makes its TIN and hands it to the run's
/// sink. Throws as runBuild does.

#include "build_run.hpp"

namespace terratin::detail {

/// Point clouds, or rasters at full resolution: every point a vertex, exactly Delaunay (and
/// constrained, with breaklines or areas).
BuildReport buildPointTin(BuildRun& run);

/// A DEM simplified (options.refine), whole or in tiles (options.refine->tileSize), with
/// constraints when whole.
BuildReport buildRefinedTin(BuildRun& run);

/// What the simplified and tiled builds refuse of the options alone (a usage error, found
/// before anything is read): InvalidInputError. Needs options.refine.
void checkDemOnlyOptions(const BuildOptions& options);

} // namespace terratin::detail

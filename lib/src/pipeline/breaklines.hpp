#pragma once
/// @file
/// The breaklines stage of a build: OGR lines read, put into the TIN's CRS, clipped to its
/// hull, given elevations, and inserted as constraints (docs/cli.md, --breaklines).

#include "terratin/constrain/constrained_tin.hpp"
#include "terratin/pipeline/build_pipeline.hpp"

#include <string>

namespace terratin::detail {

/// `mesh` (the Delaunay TIN of the inputs, in `crsWkt`) with every line of
/// options.breaklines inserted: a constrained Delaunay TIN. Lines are reprojected from their
/// layer's CRS (a layer without one is taken to be in `crsWkt`, with a notice), clipped to the
/// mesh's convex hull (with a notice), and their vertices get z per options.breaklineZ. A
/// source without lines gives a notice. Fills report.breaklines, clippedBreaklines,
/// constraintVertices and constraintCrossings. Throws what io::readOgrLines and
/// insertConstraints throw, and InvalidInputError for a line without z under BreaklineZ::Line.
ConstrainedTin addBreaklines(TinMesh mesh, const BuildOptions& options, const std::string& crsWkt,
                             BuildReport& report);

} // namespace terratin::detail

#pragma once
/// @file
/// The constraints stage of a build: OGR lines (breaklines) and polygons (clip, erase and
/// replace areas) read, put into the TIN's CRS, clipped to its hull, given elevations, and inserted
/// as constraints (docs/cli.md, --breaklines, --clip, --erase).

#include "terratin/constrain/constrained_tin.hpp"
#include "terratin/io/ogr_line_reader.hpp"
#include "terratin/pipeline/build_pipeline.hpp"

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace terratin::detail {

/// A constrained TIN and the triangles to drop for --clip / --erase.
struct ConstrainedBuild {
    ConstrainedTin tin;
    /// outsideArea[t] = 1 for a triangle outside the clip area or inside the erase area; empty
    /// without either.
    std::vector<std::uint8_t> outsideArea;
    /// The areas' polygons in the TIN's CRS (nullopt: not given), to decide triangles again
    /// after more vertices go in.
    std::optional<io::LineLayer> clip;
    std::optional<io::LineLayer> erase;
    std::optional<io::LineLayer> replace;
    /// The replace rings are tin.chains[0 .. ringLevels.size()), ring r flat at ringLevels[r].
    std::vector<double> ringLevels;
};

/// The polygons of options.clip, options.erase and options.replace (nullopt where not given),
/// read and reprojected into `crsWkt` (see addConstraints).
struct ConstraintAreas {
    std::optional<io::LineLayer> clip;
    std::optional<io::LineLayer> erase;
    std::optional<io::LineLayer> replace;
};
ConstraintAreas readConstraintAreas(const BuildOptions& options, const std::string& crsWkt,
                                    BuildReport& report);

/// `mesh` (the Delaunay TIN of the inputs, in `crsWkt`) with every line of
/// options.breaklines and every ring of `areas` (readConstraintAreas) inserted: a constrained
/// Delaunay TIN. Lines and rings are reprojected from their layer's CRS (a layer without one is
/// taken to be in `crsWkt`, with a notice) and clipped to the mesh's convex hull (with a notice);
/// breakline vertices get z per options.breaklineZ, clip and erase ring vertices the surface's.
/// Replace areas are flat: the vertices inside one are left out (those on the convex hull stay, at
/// its level) and every constraint vertex on or inside one takes its level (options.replaceZField,
/// else the lowest surface elevation on its boundary). A source without features gives a notice.
/// Fills report.breaklines, clippedBreaklines, constraintVertices, constraintCrossings,
/// replacePolygons and replacedPoints. Throws what io::readOgrLines, io::readOgrPolygons and
/// insertConstraints throw, and InvalidInputError for a line without z under BreaklineZ::Line.
ConstrainedBuild addConstraints(TinMesh mesh, const BuildOptions& options,
                                const std::string& crsWkt, BuildReport& report,
                                ConstraintAreas areas);

/// Every vertex of a replace ring's chain at the ring's level: vertices lying on a ring (input
/// points, or points inserted later) are on the lake's shore line.
void flattenReplaceRings(ConstrainedBuild& build);

} // namespace terratin::detail

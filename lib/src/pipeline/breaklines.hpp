#pragma once
/// @file
/// The constraints stage of a build: OGR lines (breaklines) and polygons (clip, erase and
/// replace areas) read, put into the TIN's CRS, clipped to its hull, given elevations, and inserted
/// as constraints (docs/cli.md, --breaklines, --clip, --erase).

#include "constraint_areas.hpp"
#include "terratin/constrain/constrained_tin.hpp"
#include "terratin/geometry/height_grid.hpp"
#include "terratin/io/ogr_line_reader.hpp"
#include "terratin/pipeline/build_pipeline.hpp"

#include <cstdint>
#include <future>
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
    /// Where the areas' rings (clip, erase and replace) were cut at the hull: for regionsWhere.
    std::vector<OpenRingEnd> openRingEnds;
};

/// The polygons of options.clip, options.erase and options.replace (nullopt where not given)
/// and the lines of each options.breaklines source, in the TIN's CRS. They are read before the
/// TIN is built: a bad layer fails before the long part, and their vertices size the TIN's
/// arrays.
struct ConstraintSources {
    std::optional<io::LineLayer> clip;
    std::optional<io::LineLayer> erase;
    std::optional<io::LineLayer> replace;
    std::vector<io::LineLayer> breaklines;

    /// The room to leave in the TIN's arrays (TriangulationOptions::spareVertices): twice the
    /// vertices of every line and ring, for them and for the crossings and cells inserted
    /// after them.
    [[nodiscard]] std::size_t spareVertices() const;
    /// How many lines and rings there are in all.
    [[nodiscard]] std::size_t lineCount() const;

private:
    /// Calls visit(layer) for every layer given.
    template <class Visit> void forEachLayer(Visit&& visit) const;
};
/// The layers of options.clip, options.erase, options.replace and options.breaklines as read
/// (nullopt where not given), in their own CRS.
struct ConstraintLayers {
    std::optional<io::LineLayer> clip;
    std::optional<io::LineLayer> erase;
    std::optional<io::LineLayer> replace;
    std::vector<io::LineLayer> breaklines;
};

/// Reads the layers of `options`' constraints. Throws what io::readOgrLines and
/// io::readOgrPolygons throw.
ConstraintLayers readConstraintLayers(const BuildOptions& options);

/// readConstraintLayers on a thread of its own, so that the read overlaps the inputs' (GDAL
/// reads different datasets on different threads). `options` must outlive the future.
std::future<ConstraintLayers> startReadingConstraintLayers(const BuildOptions& options);

/// The constraint sources from `layers` (readConstraintLayers), reprojected from their layer's
/// CRS into `crsWkt` (a layer without one is taken to be in `crsWkt`, with a notice; so is a
/// source without features). The vertices that take the surface's z (breaklines per
/// options.breaklineZ, clip and erase rings) get `dem`'s bilinear elevation where it has one
/// (bilinearElevation), else NaN, for the TIN's to fill (addConstraints); `dem` is the only
/// input raster when the TIN's points are its cell centres, else null. Throws CrsError for a
/// layer that cannot be reprojected, and InvalidInputError for a line without z under
/// BreaklineZ::Line.
ConstraintSources readConstraintSources(ConstraintLayers layers, const BuildOptions& options,
                                        const std::string& crsWkt, const HeightGrid* dem,
                                        BuildReport& report);

/// `mesh` (the Delaunay TIN of the inputs, in the sources' CRS, or the refiner's TIN with its
/// triangles over holes: a mesh that covers its convex hull) with every line and ring of
/// `sources` inserted: a constrained Delaunay TIN. Lines and rings are clipped to the mesh's
/// convex hull (with a notice); a vertex still without z (readConstraintSources) takes the
/// mesh's surface, linear in the triangle holding it. Replace areas are flat: the vertices inside
/// one are left out (those on the convex hull stay, at its level) and every constraint vertex on or
/// inside one takes its level (options.replaceZField, else the lowest surface elevation on its
/// boundary). Fills report.breaklines, clippedBreaklines, constraintVertices, constraintCrossings,
/// replacePolygons and replacedPoints. `progress` goes to insertConstraints, which calls it
/// every few milliseconds and throws Cancelled when it returns false. Throws what
/// insertConstraints throws, and InvalidInputError for a replace polygon outside the data
/// without a level.
ConstrainedBuild addConstraints(TinMesh mesh, const BuildOptions& options, BuildReport& report,
                                ConstraintSources sources, const ProgressCallback& progress = {});

/// Every vertex of a replace ring's chain at the ring's level: vertices lying on a ring (input
/// points, or points inserted later) are on the lake's shore line.
void flattenReplaceRings(ConstrainedBuild& build);

} // namespace terratin::detail

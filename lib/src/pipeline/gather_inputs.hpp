#pragma once
/// @file
/// The read stage of runBuild: every input read, brought into one CRS, scaled and merged.
/// Internal to terratin::io.

#include "terratin/geometry/height_grid.hpp"
#include "terratin/geometry/point.hpp"
#include "terratin/pipeline/build_pipeline.hpp"
#include "terratin/progress.hpp"

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace terratin::detail {

/// The merged points of all inputs.
struct GatheredInputs {
    /// Every input's points, in input order, in the target CRS.
    std::vector<Point3> points;
    /// points[offsets[i] .. offsets[i + 1]) came from input i; offsets.size() == inputs + 1.
    std::vector<std::size_t> offsets;
    /// The CRS of `points` (and of the output), empty when the inputs have none.
    std::string crsWkt;
    /// When the only input is a raster: its width and the row-major cell index of each point
    /// (for the nodes layer's row / col); 0 and empty otherwise.
    std::uint64_t rasterWidth = 0;
    std::vector<std::uint64_t> cellIndex;
    /// When the only input is a raster and its points are its cell centres (not reprojected):
    /// its height and geotransform (cellSurface); 0 otherwise.
    std::uint64_t rasterHeight = 0;
    std::array<double, 6> rasterGeoTransform{0.0, 1.0, 0.0, 0.0, 0.0, 1.0};
};

/// The only input raster's cells as a grid (its points' z, rounded to float32 as the refiner's
/// grid holds them; NaN where no point is), when `gathered` has one in place (rasterHeight);
/// nullopt otherwise. O(cells), on up to `threads` threads (0: all hardware threads).
std::optional<HeightGrid> cellSurface(const GatheredInputs& gathered, unsigned threads);

/// Reads, reprojects and merges options.inputs; fills report.inputs (all but
/// duplicates), the CRS fields, rasterCells, skippedCells, filteredOut, points, notices and
/// timings.reproject. `progress` gets the 0..1 fraction of this stage.
GatheredInputs gatherInputs(const BuildOptions& options, BuildReport& report,
                            const ProgressCallback& progress);

/// Keeps `text` in report.notices and passes it to options.notice.
void notify(const BuildOptions& options, BuildReport& report, const std::string& text);

/// The UTM/UPS zone (GeographicLib's standard zone) of `centre`, longitude and latitude in
/// degrees in `geographicWkt`, as a projected CRS on the same datum (WKT2); sets report.zone
/// and gives the notice that says so. Throws CrsError for an unusable CRS or centre.
std::string zoneOfCentre(const BuildOptions& options, BuildReport& report,
                         const std::string& geographicWkt, Point2 centre);

/// Fills report.inputs[i].duplicates from the mesh's sourceIndex: the points of input i that
/// did not become a vertex.
void countDuplicatesPerInput(const std::vector<std::size_t>& offsets,
                             std::span<const std::uint32_t> sourceIndex, BuildReport& report);

} // namespace terratin::detail

#include "refine_placement.hpp"

#include "gather_inputs.hpp"

#include "terratin/crs/grid_projection.hpp"
#include "terratin/crs/reprojection.hpp"
#include "terratin/error.hpp"
#include "terratin/pipeline/build_option_table.hpp"

#include <chrono>

namespace terratin::detail {

RefinePlacement placeRefinedCells(const BuildOptions& options, const HeightGrid& grid,
                                  const std::string& rasterWkt, BuildReport& report) {
    const auto start = std::chrono::steady_clock::now();
    const std::string sourceOption = optionName("s_srs", options.optionSpelling);
    const std::string targetOption = optionName("t_srs", options.optionSpelling);
    const std::string source = options.sourceSrs.empty()
                                   ? rasterWkt
                                   : crs::crsFromUserInput(options.sourceSrs, sourceOption);
    const std::string requested = options.targetSrs.empty()
                                      ? std::string()
                                      : crs::crsFromUserInput(options.targetSrs, targetOption);
    if (source.empty() && !requested.empty())
        throw CrsError("CRS: '" + report.input + "' has no CRS and " + targetOption +
                       " asks to reproject it; give its CRS with " + sourceOption);
    const crs::CrsDescription sourceDescription = crs::describeCrs(source);
    report.sourceCrsName = sourceDescription.name;
    report.sourceCrsCode = sourceDescription.code;

    RefinePlacement placement;
    placement.targetWkt = requested.empty() ? source : requested;
    if (requested.empty() && !options.keepGeographic && sourceDescription.geographic)
        placement.targetWkt = zoneOfCentre(options, report, source, grid.extentCentre());
    if (!requested.empty() && crs::describeCrs(requested).geographic)
        notify(options, report,
               targetOption + " is geographic: the TIN is triangulated in degrees");
    if (!crs::sameCrs(source, placement.targetWkt)) {
        placement.positions = crs::projectCellCentres(grid, source, placement.targetWkt);
        report.reprojected = true;
    }
    report.timings.reproject =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return placement;
}

} // namespace terratin::detail

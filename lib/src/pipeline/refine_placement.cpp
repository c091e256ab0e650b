#include "refine_placement.hpp"

#include "gather_inputs.hpp"

#include "terratin/crs/grid_projection.hpp"
#include "terratin/crs/reprojection.hpp"
#include "terratin/error.hpp"
#include "terratin/pipeline/build_option_table.hpp"

#include <chrono>

namespace terratin::detail {

bool RefineCrs::movesCells() const {
    return !crs::sameCrs(source, target);
}

RefineCrs chooseRefineCrs(const BuildOptions& options, Point2 centre, const std::string& rasterWkt,
                          BuildReport& report) {
    const std::string sourceOption = markOption("s_srs");
    const std::string targetOption = markOption("t_srs");
    RefineCrs chosen;
    chosen.source = options.sourceSrs.empty()
                        ? rasterWkt
                        : crs::crsFromUserInput(options.sourceSrs, sourceOption);
    const std::string requested = options.targetSrs.empty()
                                      ? std::string()
                                      : crs::crsFromUserInput(options.targetSrs, targetOption);
    if (chosen.source.empty() && !requested.empty())
        throw CrsError("CRS: '" + report.input + "' has no CRS and " + targetOption +
                       " asks to reproject it; give its CRS with " + sourceOption);
    const crs::CrsDescription sourceDescription = crs::describeCrs(chosen.source);
    report.sourceCrsName = sourceDescription.name;
    report.sourceCrsCode = sourceDescription.code;

    chosen.target = requested.empty() ? chosen.source : requested;
    if (requested.empty() && !options.keepGeographic && sourceDescription.geographic)
        chosen.target = zoneOfCentre(options, report, chosen.source, centre);
    if (!requested.empty() && crs::describeCrs(requested).geographic)
        notify(options, report,
               targetOption + " is geographic: the TIN is triangulated in degrees");
    return chosen;
}

RefinePlacement placeRefinedCells(const BuildOptions& options, const HeightGrid& grid,
                                  const std::string& rasterWkt, BuildReport& report) {
    const auto start = std::chrono::steady_clock::now();
    const RefineCrs chosen = chooseRefineCrs(options, grid.extentCentre(), rasterWkt, report);
    RefinePlacement placement;
    placement.targetWkt = chosen.target;
    if (chosen.movesCells()) {
        placement.positions = crs::projectCellCentres(grid, chosen.source, chosen.target);
        report.reprojected = true;
    }
    report.timings.reproject =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return placement;
}

} // namespace terratin::detail

#include "refine_placement.hpp"

#include "gather_inputs.hpp"

#include "terratin/crs/reprojection.hpp"
#include "terratin/error.hpp"

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <chrono>
#include <optional>

namespace terratin::detail {

namespace {

/// Rows a task reprojects at a time: a few thousand cells per PROJ call.
constexpr std::size_t kRowGrain = 4;

/// Every cell centre of `grid`, from `sourceWkt` to `targetWkt`, row-major. PROJ objects are
/// not thread-safe: one Reprojector per thread.
std::vector<Point2> projectCellCentres(const HeightGrid& grid, const std::string& sourceWkt,
                                       const std::string& targetWkt) {
    const crs::Reprojector first(sourceWkt, targetWkt); // throws here, on the calling thread
    tbb::enumerable_thread_specific<std::optional<crs::Reprojector>> reprojectors;
    const auto width = static_cast<std::size_t>(grid.width);
    std::vector<Point2> positions(grid.cellCount());
    tbb::parallel_for(
        tbb::blocked_range<std::size_t>(0, static_cast<std::size_t>(grid.height), kRowGrain),
        [&](const tbb::blocked_range<std::size_t>& rows) {
            std::optional<crs::Reprojector>& reprojector = reprojectors.local();
            if (!reprojector)
                reprojector.emplace(sourceWkt, targetWkt);
            std::vector<Point3> centres;
            centres.reserve(rows.size() * width);
            for (std::size_t row = rows.begin(); row < rows.end(); ++row)
                for (std::size_t col = 0; col < width; ++col) {
                    const Point2 centre = grid.cellCentre(static_cast<std::int64_t>(row),
                                                          static_cast<std::int64_t>(col));
                    centres.push_back({centre.x, centre.y, 0.0});
                }
            reprojector->transform(centres);
            Point2* out = positions.data() + rows.begin() * width;
            for (const Point3& p : centres)
                *out++ = {p.x, p.y};
        });
    return positions;
}

/// The georeferenced centre of the raster's extent.
Point2 extentCentre(const HeightGrid& grid) {
    const double px = 0.5 * static_cast<double>(grid.width);
    const double py = 0.5 * static_cast<double>(grid.height);
    const std::array<double, 6>& c = grid.geoTransform;
    return {c[0] + px * c[1] + py * c[2], c[3] + px * c[4] + py * c[5]};
}

} // namespace

RefinePlacement placeRefinedCells(const BuildOptions& options, const HeightGrid& grid,
                                  const std::string& rasterWkt, BuildReport& report) {
    const auto start = std::chrono::steady_clock::now();
    const std::string source = options.sourceSrs.empty()
                                   ? rasterWkt
                                   : crs::crsFromUserInput(options.sourceSrs, "--s_srs");
    const std::string requested = options.targetSrs.empty()
                                      ? std::string()
                                      : crs::crsFromUserInput(options.targetSrs, "--t_srs");
    if (source.empty() && !requested.empty())
        throw CrsError("CRS: '" + report.input +
                       "' has no CRS and --t_srs asks to reproject it; give its CRS with --s_srs");
    const crs::CrsDescription sourceDescription = crs::describeCrs(source);
    report.sourceCrsName = sourceDescription.name;
    report.sourceCrsCode = sourceDescription.code;

    RefinePlacement placement;
    placement.targetWkt = requested.empty() ? source : requested;
    if (requested.empty() && !options.keepGeographic && sourceDescription.geographic)
        placement.targetWkt = zoneOfCentre(options, report, source, extentCentre(grid));
    if (!requested.empty() && crs::describeCrs(requested).geographic)
        notify(options, report, "--t_srs is geographic: the TIN is triangulated in degrees");
    if (!crs::sameCrs(source, placement.targetWkt)) {
        placement.positions = projectCellCentres(grid, source, placement.targetWkt);
        report.reprojected = true;
    }
    report.timings.reproject =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return placement;
}

} // namespace terratin::detail

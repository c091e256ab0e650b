/// @file
/// The read stage of runBuild (see gather_inputs.hpp).
///
/// CRS decision, in order:
/// 1. each input's CRS is its own, or --s_srs for all of them;
/// 2. an input without CRS is an error when the run needs one (a --t_srs, or another input
///    with a CRS); inputs that all lack one are merged as they are;
/// 3. the target is --t_srs, else the first input's CRS;
/// 4. a geographic target that the user did not ask for (no --t_srs, no --keep-geographic)
///    becomes the UTM/UPS zone of the data's centre (GeographicLib's StandardZone), on the
///    same datum, with a notice;
/// 5. every input not already in the target is reprojected (x, y only).

#include "gather_inputs.hpp"

#include "terratin/crs/reprojection.hpp"
#include "terratin/crs/utm_zone.hpp"
#include "terratin/error.hpp"
#include "terratin/io/input_reader.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>

namespace terratin::detail {

namespace {

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point start) {
    return std::chrono::duration<double>(Clock::now() - start).count();
}

/// Centre of the bounding box of every point, in the (common geographic) CRS of the points.
Point2 boundingBoxCentre(const std::vector<io::PointCloud>& clouds) {
    double minX = std::numeric_limits<double>::infinity();
    double minY = minX;
    double maxX = -minX;
    double maxY = -minX;
    for (const io::PointCloud& cloud : clouds)
        for (const Point3& p : cloud.points) {
            minX = std::min(minX, p.x);
            maxX = std::max(maxX, p.x);
            minY = std::min(minY, p.y);
            maxY = std::max(maxY, p.y);
        }
    return {0.5 * (minX + maxX), 0.5 * (minY + maxY)};
}

void reprojectInto(io::PointCloud& cloud, std::string& cloudCrs, const std::string& targetWkt,
                   InputReport& input) {
    if (crs::sameCrs(cloudCrs, targetWkt))
        return;
    const crs::Reprojector reprojector(cloudCrs, targetWkt);
    reprojector.transform(cloud.points);
    cloudCrs = targetWkt;
    input.reprojected = true;
}

} // namespace

void notify(const BuildOptions& options, BuildReport& report, const std::string& text) {
    report.notices.push_back(text);
    if (options.notice)
        options.notice(text);
}

std::string zoneOfCentre(const BuildOptions& options, BuildReport& report,
                         const std::string& geographicWkt, Point2 centre) {
    const crs::UtmZone zone = crs::standardUtmZone(centre.x, centre.y);
    const std::string geographicName = crs::describeCrs(geographicWkt).name;
    const std::string target = crs::utmZoneCrs(zone, geographicWkt);
    report.zone = zone.name();
    const crs::CrsDescription projected = crs::describeCrs(target);
    const std::string label =
        projected.code.empty() ? projected.name : projected.name + " [" + projected.code + "]";
    char centreText[96];
    std::snprintf(centreText, sizeof centreText, "%.6f, %.6f", centre.x, centre.y);
    notify(options, report,
           "the input is geographic (" + geographicName + "); projecting it to " + zone.name() +
               " (" + label + "), the zone of its centre (" + centreText +
               "); use --t_srs to choose another CRS or --keep-geographic "
               "to triangulate in degrees");
    return target;
}

GatheredInputs gatherInputs(const BuildOptions& options, BuildReport& report,
                            const ProgressCallback& progress) {
    const std::vector<std::string> paths = options.inputPaths();
    if (paths.empty() || std::any_of(paths.begin(), paths.end(),
                                     [](const std::string& path) { return path.empty(); }))
        throw InvalidInputError("Input: no input file given");
    if (!std::isfinite(options.zFactor) || options.zFactor == 0.0)
        throw InvalidInputError("Input: --z-factor must be a finite number other than 0");
    report.zFactor = options.zFactor;

    // The user's CRSs first: a typo should fail before minutes of reading.
    const std::string sourceOverride = options.sourceSrs.empty()
                                           ? std::string()
                                           : crs::crsFromUserInput(options.sourceSrs, "--s_srs");
    const std::string requestedTarget = options.targetSrs.empty()
                                            ? std::string()
                                            : crs::crsFromUserInput(options.targetSrs, "--t_srs");

    io::InputReadOptions readOptions;
    readOptions.raster.band = options.band;
    readOptions.las.classes = options.lasClasses;
    readOptions.las.returns = options.lasReturns;
    readOptions.text.columns = options.textColumns;
    readOptions.vector.zField = options.zField;
    readOptions.vector.layer = options.inputLayer;

    // Read every input; each gets an equal share of this stage's progress.
    std::vector<io::PointCloud> clouds;
    std::vector<std::string> cloudCrs;
    const double share = 0.9 / static_cast<double>(paths.size());
    for (std::size_t i = 0; i < paths.size(); ++i) {
        ProgressCallback inputProgress;
        if (progress)
            inputProgress = [&progress, i, share](double fraction, std::string_view message) {
                return progress(static_cast<double>(i) * share + fraction * share, message);
            };
        clouds.push_back(io::readInput(paths[i], readOptions, inputProgress));
        const io::PointCloud& cloud = clouds.back();
        cloudCrs.push_back(sourceOverride.empty() ? cloud.crsWkt : sourceOverride);
        const crs::CrsDescription description = crs::describeCrs(cloudCrs.back());
        InputReport input;
        input.path = paths[i];
        input.kind = io::toString(cloud.kind);
        input.crsName = description.name;
        input.crsCode = description.code;
        input.records = cloud.recordsRead;
        input.filteredOut = cloud.filteredOut;
        input.skippedCells = cloud.skippedCells;
        input.points = cloud.points.size();
        report.inputs.push_back(input);
        if (cloud.kind == io::InputKind::Raster)
            report.rasterCells += cloud.recordsRead;
        report.skippedCells += cloud.skippedCells;
        report.filteredOut += cloud.filteredOut;
        report.points += cloud.points.size();
    }

    const Clock::time_point reprojectStart = Clock::now();
    // An input without a CRS, when another has one or a target is asked for.
    const auto withCrs = std::count_if(cloudCrs.begin(), cloudCrs.end(),
                                       [](const std::string& wkt) { return !wkt.empty(); });
    if (withCrs < static_cast<std::ptrdiff_t>(clouds.size()) &&
        (withCrs > 0 || !requestedTarget.empty())) {
        const auto missing = static_cast<std::size_t>(
            std::find(cloudCrs.begin(), cloudCrs.end(), std::string()) - cloudCrs.begin());
        throw CrsError("CRS: '" + paths[missing] + "' has no CRS and " +
                       (requestedTarget.empty() ? std::string("other inputs have one")
                                                : std::string("--t_srs asks to reproject it")) +
                       "; give its CRS with --s_srs");
    }

    // The source CRS of the report: the one all inputs share, or "several".
    bool allSame = true;
    for (std::size_t i = 1; i < cloudCrs.size() && allSame; ++i)
        allSame = crs::sameCrs(cloudCrs[i], cloudCrs[0]);
    if (allSame) {
        report.sourceCrsName = report.inputs.front().crsName;
        report.sourceCrsCode = report.inputs.front().crsCode;
    } else {
        report.sourceCrsName = "several";
    }

    std::string target = requestedTarget.empty() ? cloudCrs.front() : requestedTarget;
    if (!target.empty() && requestedTarget.empty() && !options.keepGeographic &&
        crs::describeCrs(target).geographic) {
        // Degrees are not a plane: bring everything into the geographic CRS, find the centre,
        // and project to its zone on the same datum.
        for (std::size_t i = 0; i < clouds.size(); ++i)
            reprojectInto(clouds[i], cloudCrs[i], target, report.inputs[i]);
        target = zoneOfCentre(options, report, target, boundingBoxCentre(clouds));
    }

    // Units: z is never converted; say so when x, y change units and z is left alone.
    const crs::CrsDescription targetDescription = crs::describeCrs(target);
    for (std::size_t i = 0; i < clouds.size(); ++i) {
        const crs::CrsDescription source = crs::describeCrs(cloudCrs[i]);
        reprojectInto(clouds[i], cloudCrs[i], target, report.inputs[i]);
        if (report.inputs[i].reprojected && options.zFactor == 1.0 && source.projected &&
            targetDescription.projected &&
            source.metresPerUnit != targetDescription.metresPerUnit) {
            char factor[64];
            std::snprintf(factor, sizeof factor, "%.10g",
                          source.metresPerUnit / targetDescription.metresPerUnit);
            notify(options, report,
                   "'" + paths[i] + "' has x, y in " + source.linearUnit + " and the output in " +
                       targetDescription.linearUnit +
                       ": elevations stay in the input's units (use --z-factor " + factor +
                       " if they share the horizontal unit)");
        }
        report.reprojected = report.reprojected || report.inputs[i].reprojected;
    }
    if (!requestedTarget.empty() && targetDescription.geographic)
        notify(options, report, "--t_srs is geographic: the TIN is triangulated in degrees");
    report.timings.reproject = secondsSince(reprojectStart);

    // Merge in input order, applying the z factor; each cloud is released once copied.
    GatheredInputs gathered;
    gathered.crsWkt = target;
    gathered.offsets.push_back(0);
    if (clouds.size() == 1) {
        gathered.points = std::move(clouds.front().points);
        gathered.rasterWidth = clouds.front().rasterWidth;
        gathered.cellIndex = std::move(clouds.front().cellIndex);
    } else {
        std::size_t total = 0;
        for (const io::PointCloud& cloud : clouds)
            total += cloud.points.size();
        gathered.points.reserve(total);
        for (io::PointCloud& cloud : clouds) {
            gathered.points.insert(gathered.points.end(), cloud.points.begin(), cloud.points.end());
            cloud.points = {};
        }
    }
    for (const InputReport& input : report.inputs)
        gathered.offsets.push_back(gathered.offsets.back() + input.points);
    if (options.zFactor != 1.0)
        for (Point3& p : gathered.points)
            p.z *= options.zFactor;
    if (progress)
        progress(1.0, "read");
    return gathered;
}

void countDuplicatesPerInput(const std::vector<std::size_t>& offsets,
                             std::span<const std::uint32_t> sourceIndex, BuildReport& report) {
    std::vector<std::uint64_t> vertices(report.inputs.size(), 0);
    for (const std::uint32_t index : sourceIndex) {
        const auto input = static_cast<std::size_t>(
            std::upper_bound(offsets.begin(), offsets.end(), std::size_t{index}) - offsets.begin() -
            1);
        if (input < vertices.size())
            ++vertices[input];
    }
    for (std::size_t i = 0; i < report.inputs.size(); ++i)
        report.inputs[i].duplicates = report.inputs[i].points - vertices[i];
}

} // namespace terratin::detail

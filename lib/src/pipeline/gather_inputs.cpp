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

#include "../parallel/parallel_for.hpp"
#include "../stopwatch.hpp"

#include "terratin/crs/reprojection.hpp"
#include "terratin/crs/utm_zone.hpp"
#include "terratin/error.hpp"
#include "terratin/io/input_reader.hpp"
#include "terratin/pipeline/build_option_table.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

namespace terratin::detail {

namespace {

/// Of this stage's progress, the part that reading the files reports, shared equally among
/// them; reprojecting and merging, which report nothing themselves, take the rest.
constexpr double kReadFilesShare = 0.9;

/// One input as read, with the CRS it is in now: its own, or --s_srs; the target CRS once
/// reprojected.
struct ReadInput {
    io::PointCloud cloud;
    std::string crsWkt;
};

/// The CRSs the user named, as WKT; empty when not given.
struct UserCrs {
    std::string source;
    std::string target;
};

void checkInputPaths(const std::vector<std::string>& paths) {
    if (paths.empty() || std::any_of(paths.begin(), paths.end(),
                                     [](const std::string& path) { return path.empty(); }))
        throw InvalidInputError("Input: no input file given");
}

/// The user's CRSs, parsed before any reading: a typo should fail before minutes of reading.
UserCrs parseUserCrs(const BuildOptions& options) {
    UserCrs user;
    if (!options.sourceSrs.empty())
        user.source = crs::crsFromUserInput(options.sourceSrs, markOption("s_srs"));
    if (!options.targetSrs.empty())
        user.target = crs::crsFromUserInput(options.targetSrs, markOption("t_srs"));
    return user;
}

io::InputReadOptions readOptionsOf(const BuildOptions& options) {
    io::InputReadOptions read;
    read.raster.band = options.band;
    read.las.classes = options.lasClasses;
    read.las.returns = options.lasReturns;
    read.las.threads = options.triangulation.threads;
    read.text.columns = options.textColumns;
    read.vector.zField = options.zField;
    read.vector.layer = options.inputLayer;
    return read;
}

/// The report's entry for one input as read (duplicates and reprojection come later).
InputReport describeInput(const std::string& path, const ReadInput& input) {
    const crs::CrsDescription description = crs::describeCrs(input.crsWkt);
    InputReport entry;
    entry.path = path;
    entry.kind = io::toString(input.cloud.kind);
    entry.crsName = description.name;
    entry.crsCode = description.code;
    entry.records = input.cloud.recordsRead;
    entry.filteredOut = input.cloud.filteredOut;
    entry.skippedCells = input.cloud.skippedCells;
    entry.points = input.cloud.points.size();
    return entry;
}

void addToTotals(const io::PointCloud& cloud, BuildReport& report) {
    if (cloud.kind == io::InputKind::Raster)
        report.rasterCells += cloud.recordsRead;
    report.skippedCells += cloud.skippedCells;
    report.filteredOut += cloud.filteredOut;
    report.points += cloud.points.size();
}

/// Reads every input in order, each reporting its equal share of `progress`.
std::vector<ReadInput> readInputs(const std::vector<std::string>& paths,
                                  const BuildOptions& options, const std::string& sourceOverride,
                                  BuildReport& report, const ProgressCallback& progress) {
    const io::InputReadOptions readOptions = readOptionsOf(options);
    const double share = kReadFilesShare / static_cast<double>(paths.size());
    std::vector<ReadInput> inputs;
    for (std::size_t i = 0; i < paths.size(); ++i) {
        const ProgressCallback inputProgress =
            phaseProgress(progress, static_cast<double>(i) * share, share);
        ReadInput input{io::readInput(paths[i], readOptions, inputProgress), {}};
        input.crsWkt = sourceOverride.empty() ? input.cloud.crsWkt : sourceOverride;
        report.inputs.push_back(describeInput(paths[i], input));
        addToTotals(input.cloud, report);
        inputs.push_back(std::move(input));
    }
    return inputs;
}

/// Inputs without a CRS are merged as they are only when none has one and no target is asked
/// for: otherwise they could not be brought into one CRS.
void requireCrsWhereNeeded(const std::vector<ReadInput>& inputs, const BuildOptions& options,
                           const std::string& requestedTarget) {
    const auto missing = std::find_if(inputs.begin(), inputs.end(),
                                      [](const ReadInput& input) { return input.crsWkt.empty(); });
    if (missing == inputs.end())
        return;
    const bool otherHasCrs = std::any_of(
        inputs.begin(), inputs.end(), [](const ReadInput& input) { return !input.crsWkt.empty(); });
    if (!otherHasCrs && requestedTarget.empty())
        return;
    throw CrsError("CRS: '" + options.inputs[static_cast<std::size_t>(missing - inputs.begin())] +
                   "' has no CRS and " +
                   (requestedTarget.empty() ? std::string("other inputs have one")
                                            : markOption("t_srs") + " asks to reproject it") +
                   "; give its CRS with " + markOption("s_srs"));
}

/// The report's source CRS: the one every input shares, or "several".
void reportSourceCrs(const std::vector<ReadInput>& inputs, BuildReport& report) {
    const bool allSame =
        std::all_of(inputs.begin(), inputs.end(), [&inputs](const ReadInput& input) {
            return crs::sameCrs(input.crsWkt, inputs.front().crsWkt);
        });
    if (allSame) {
        report.sourceCrsName = report.inputs.front().crsName;
        report.sourceCrsCode = report.inputs.front().crsCode;
    } else {
        report.sourceCrsName = "several";
    }
}

/// Centre of the bounding box of every point, in the (common geographic) CRS of the points.
Point2 boundingBoxCentre(const std::vector<ReadInput>& inputs) {
    double minX = std::numeric_limits<double>::infinity();
    double minY = minX;
    double maxX = -minX;
    double maxY = -minX;
    for (const ReadInput& input : inputs)
        for (const Point3& p : input.cloud.points) {
            minX = std::min(minX, p.x);
            maxX = std::max(maxX, p.x);
            minY = std::min(minY, p.y);
            maxY = std::max(maxY, p.y);
        }
    return {0.5 * (minX + maxX), 0.5 * (minY + maxY)};
}

/// Transforms x, y of `input` into `targetWkt` unless it is there already.
void reprojectInto(ReadInput& input, const std::string& targetWkt, InputReport& entry) {
    if (crs::sameCrs(input.crsWkt, targetWkt))
        return;
    const crs::Reprojector reprojector(input.crsWkt, targetWkt);
    reprojector.transform(input.cloud.points);
    input.crsWkt = targetWkt;
    entry.reprojected = true;
}

/// The target CRS: --t_srs, else the first input's CRS, except that a geographic one the user
/// did not ask to keep becomes the UTM/UPS zone of the data's centre. To find that centre,
/// every input is first brought into the geographic CRS.
std::string chooseTargetCrs(const BuildOptions& options, const std::string& requestedTarget,
                            std::vector<ReadInput>& inputs, BuildReport& report) {
    if (!requestedTarget.empty())
        return requestedTarget;
    const std::string first = inputs.front().crsWkt;
    if (first.empty() || options.keepGeographic || !crs::describeCrs(first).geographic)
        return first;
    for (std::size_t i = 0; i < inputs.size(); ++i)
        reprojectInto(inputs[i], first, report.inputs[i]);
    return zoneOfCentre(options, report, first, boundingBoxCentre(inputs));
}

/// z is never converted: says so when an input's x, y change units and --z-factor is 1.
void noticeUnitChange(const BuildOptions& options, BuildReport& report, const std::string& path,
                      const crs::CrsDescription& source, const crs::CrsDescription& target) {
    if (options.zFactor != 1.0 || !source.projected || !target.projected ||
        source.metresPerUnit == target.metresPerUnit)
        return;
    char factor[64];
    std::snprintf(factor, sizeof factor, "%.10g", source.metresPerUnit / target.metresPerUnit);
    notify(options, report,
           "'" + path + "' has x, y in " + source.linearUnit + " and the output in " +
               target.linearUnit + ": elevations stay in the input's units (use " +
               markOption("z_factor") + " " + factor + " if they share the horizontal unit)");
}

void reprojectAll(const BuildOptions& options, const std::string& targetWkt,
                  std::vector<ReadInput>& inputs, BuildReport& report) {
    const crs::CrsDescription target = crs::describeCrs(targetWkt);
    for (std::size_t i = 0; i < inputs.size(); ++i) {
        InputReport& entry = report.inputs[i];
        const crs::CrsDescription source = crs::describeCrs(inputs[i].crsWkt);
        reprojectInto(inputs[i], targetWkt, entry);
        if (entry.reprojected)
            noticeUnitChange(options, report, entry.path, source, target);
        report.reprojected = report.reprojected || entry.reprojected;
    }
}

/// Every input's points in input order, z scaled by `zFactor`; each cloud is released once
/// copied. A single raster keeps its cell indices for the nodes layer.
GatheredInputs mergeInputs(std::vector<ReadInput>& inputs, double zFactor) {
    GatheredInputs gathered;
    gathered.offsets.push_back(0);
    for (const ReadInput& input : inputs)
        gathered.offsets.push_back(gathered.offsets.back() + input.cloud.points.size());
    if (inputs.size() == 1) {
        io::PointCloud& cloud = inputs.front().cloud;
        gathered.points = std::move(cloud.points);
        gathered.rasterWidth = cloud.rasterWidth;
        gathered.cellIndex = std::move(cloud.cellIndex);
        gathered.rasterHeight = cloud.rasterHeight;
        gathered.rasterGeoTransform = cloud.rasterGeoTransform;
    } else {
        gathered.points.reserve(gathered.offsets.back());
        for (ReadInput& input : inputs) {
            std::vector<Point3>& points = input.cloud.points;
            gathered.points.insert(gathered.points.end(), points.begin(), points.end());
            points = {};
        }
    }
    if (zFactor != 1.0)
        for (Point3& p : gathered.points)
            p.z *= zFactor;
    return gathered;
}

} // namespace

void notify(const BuildOptions& options, BuildReport& report, const std::string& text) {
    // The options a notice names are marked (markOption) and named here the caller's way.
    const std::string named = nameMarkedOptions(text, optionNaming(options.optionSpelling));
    report.notices.push_back(named);
    if (options.notice)
        options.notice(named);
}

std::string zoneOfCentre(const BuildOptions& options, BuildReport& report,
                         const std::string& geographicWkt, Point2 centre) {
    const crs::UtmZone zone = crs::standardUtmZone(centre.x, centre.y);
    const std::string geographicName = crs::describeCrs(geographicWkt).name;
    std::string target = crs::utmZoneCrs(zone, geographicWkt);
    report.zone = zone.name();
    const crs::CrsDescription projected = crs::describeCrs(target);
    const std::string label =
        projected.code.empty() ? projected.name : projected.name + " [" + projected.code + "]";
    char centreText[96];
    std::snprintf(centreText, sizeof centreText, "%.6f, %.6f", centre.x, centre.y);
    notify(options, report,
           "the input is geographic (" + geographicName + "); projecting it to " + zone.name() +
               " (" + label + "), the zone of its centre (" + centreText + "); use " +
               markOption("t_srs") + " to choose another CRS or " + markOption("keep_geographic") +
               " to triangulate in degrees");
    return target;
}

GatheredInputs gatherInputs(const BuildOptions& options, BuildReport& report,
                            const ProgressCallback& progress) {
    const std::vector<std::string>& paths = options.inputs;
    checkInputPaths(paths); // the options were checked before (checkBuildOptions)
    report.zFactor = options.zFactor;
    const UserCrs user = parseUserCrs(options);

    std::vector<ReadInput> inputs = readInputs(paths, options, user.source, report, progress);

    const Stopwatch reprojectTime;
    requireCrsWhereNeeded(inputs, options, user.target);
    reportSourceCrs(inputs, report);
    const std::string target = chooseTargetCrs(options, user.target, inputs, report);
    reprojectAll(options, target, inputs, report);
    if (!user.target.empty() && crs::describeCrs(target).geographic)
        notify(options, report,
               markOption("t_srs") + " is geographic: the TIN is triangulated in degrees");
    report.timings.reproject = reprojectTime.seconds();

    GatheredInputs gathered = mergeInputs(inputs, options.zFactor);
    gathered.crsWkt = target;
    if (report.reprojected)
        gathered.rasterHeight = 0; // the points are no longer at the cells' centres
    if (progress)
        progress(1.0, "read");
    return gathered;
}

std::optional<HeightGrid> cellSurface(const GatheredInputs& gathered, unsigned threads) {
    if (gathered.rasterWidth == 0 || gathered.rasterHeight == 0)
        return std::nullopt;
    HeightGrid grid;
    grid.width = static_cast<int>(gathered.rasterWidth);
    grid.height = static_cast<int>(gathered.rasterHeight);
    grid.geoTransform = gathered.rasterGeoTransform;
    grid.z.assign(grid.cellCount(), std::numeric_limits<float>::quiet_NaN());
    // Each point to its own cell (NaN stays NaN in float32).
    parallelFor(gathered.cellIndex.size(), threadsOrAll(threads),
                [&](unsigned, std::size_t begin, std::size_t end) {
                    for (std::size_t i = begin; i < end; ++i)
                        grid.z[gathered.cellIndex[i]] = static_cast<float>(gathered.points[i].z);
                });
    return grid;
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

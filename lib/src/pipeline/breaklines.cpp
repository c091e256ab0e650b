#include "breaklines.hpp"

#include "gather_inputs.hpp"
#include "terratin/constrain/insert_constraints.hpp"
#include "terratin/crs/reprojection.hpp"
#include "terratin/error.hpp"
#include "terratin/io/ogr_line_reader.hpp"
#include "terratin/pipeline/build_option_table.hpp"
#include "terratin/triangulate/tin_locator.hpp"

#include <algorithm>
#include <cmath>
#include <span>

namespace terratin::detail {

namespace {

/// The lines of one source in `crsWkt`.
io::LineLayer readInCrs(const std::string& source, const BuildOptions& options,
                        const std::string& crsWkt, BuildReport& report) {
    const std::string option = optionName("breaklines", options.optionSpelling);
    io::LineLayer layer = io::readOgrLines(source, options.breaklinesLayer, option);
    const std::string name = option + " '" + source + "' layer '" + layer.layerName + "'";
    if (layer.lines.empty()) {
        notify(options, report, name + " has no lines");
        return layer;
    }
    if (layer.crsWkt.empty() || crsWkt.empty()) {
        if (layer.crsWkt.empty() != crsWkt.empty())
            notify(options, report,
                   name + (layer.crsWkt.empty() ? " has no CRS: its coordinates are taken to be "
                                                  "in the TIN's CRS"
                                                : " has a CRS and the inputs none: its "
                                                  "coordinates are taken as they are"));
        return layer;
    }
    if (!crs::sameCrs(layer.crsWkt, crsWkt)) {
        const crs::Reprojector reprojector(layer.crsWkt, crsWkt);
        for (std::vector<Point3>& line : layer.lines)
            reprojector.transform(std::span<Point3>(line));
    }
    return layer;
}

/// Whether two polylines have the same points in x and y (z may have been filled in).
bool samePlaces(const std::vector<Point3>& a, const std::vector<Point3>& b) {
    return std::equal(a.begin(), a.end(), b.begin(), b.end(),
                      [](const Point3& p, const Point3& q) { return p.x == q.x && p.y == q.y; });
}

void checkLineZ(const io::LineLayer& layer, const BuildOptions& options) {
    for (std::size_t i = 0; i < layer.lines.size(); ++i)
        if (std::isnan(layer.lines[i].front().z))
            throw InvalidInputError(
                "Breaklines: " + optionName("breakline_z", options.optionSpelling) +
                " line: feature " + std::to_string(layer.featureIds[i]) + " of '" + layer.source +
                "' has no z");
}

} // namespace

ConstrainedTin addBreaklines(TinMesh mesh, const BuildOptions& options, const std::string& crsWkt,
                             BuildReport& report) {
    ConstraintSet constraints;
    {
        TinLocator locator(mesh);
        for (const std::string& source : options.breaklines) {
            io::LineLayer layer = readInCrs(source, options, crsWkt, report);
            if (options.breaklineZ == BreaklineZ::Line)
                checkLineZ(layer, options);
            std::size_t clipped = 0;
            for (std::vector<Point3>& line : layer.lines) {
                if (options.breaklineZ == BreaklineZ::Surface)
                    for (Point3& point : line)
                        point.z = std::nan("");
                std::vector<std::vector<Point3>> parts = locator.clipToHull(line);
                clipped += parts.size() != 1 || !samePlaces(parts.front(), line) ? 1 : 0;
                for (std::vector<Point3>& part : parts) {
                    // Inside the hull after clipping: the surface is defined at every point.
                    for (Point3& point : part)
                        if (std::isnan(point.z))
                            point.z = *locator.elevation({point.x, point.y});
                    constraints.polylines.push_back(std::move(part));
                }
            }
            if (clipped > 0)
                notify(options, report,
                       std::to_string(clipped) + " of the " + std::to_string(layer.lines.size()) +
                           " lines of '" + source + "' were clipped to the data's extent");
            report.clippedBreaklines += clipped;
        }
    }
    report.breaklines = constraints.polylines.size();
    ConstrainedTin constrained = insertConstraints(std::move(mesh), constraints);
    report.constraintVertices = constrained.addedPoints + constrained.intersections;
    report.constraintCrossings = constrained.intersections;
    return constrained;
}

} // namespace terratin::detail

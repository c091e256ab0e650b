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
#include <optional>
#include <span>
#include <string_view>

namespace terratin::detail {

namespace {

/// The lines (or polygon rings) of one source in `crsWkt`; `keyword` names the option it came
/// from.
io::LineLayer readInCrs(const std::string& source, std::string_view keyword,
                        const BuildOptions& options, const std::string& crsWkt,
                        BuildReport& report) {
    const std::string option = optionName(keyword, options.optionSpelling);
    io::LineLayer layer = keyword == "breaklines"
                              ? io::readOgrLines(source, options.breaklinesLayer, option)
                              : io::readOgrPolygons(source, "", option);
    const std::string name = option + " '" + source + "' layer '" + layer.layerName + "'";
    if (layer.lines.empty()) {
        notify(options, report,
               name + (keyword == "breaklines" ? " has no lines" : " has no polygons"));
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

std::size_t addLines(io::LineLayer& layer, TinLocator& locator, BreaklineZ zFrom,
                     ConstraintSet& constraints) {
    std::size_t clipped = 0;
    for (std::vector<Point3>& line : layer.lines) {
        if (zFrom == BreaklineZ::Surface)
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
    return clipped;
}

void notifyClipped(const BuildOptions& options, BuildReport& report, const std::string& source,
                   std::size_t clipped, std::size_t lines) {
    if (clipped > 0)
        notify(options, report,
               std::to_string(clipped) + " of the " + std::to_string(lines) + " lines of '" +
                   source + "' were clipped to the data's extent");
}

/// Whether `point` lies inside any polygon of `rings`: even-odd over each polygon's rings, all
/// rings in one pass: O(ring points) per query, whatever the number of polygons.
bool insideAny(const io::LineLayer& rings, Point2 point) {
    std::vector<bool> inside(rings.polygonOf.empty() ? 0 : rings.polygonOf.back() + 1, false);
    for (std::size_t r = 0; r < rings.lines.size(); ++r) {
        const std::vector<Point3>& ring = rings.lines[r];
        bool crossings = false;
        for (std::size_t i = 0, j = ring.size() - 1; i < ring.size(); j = i++)
            if ((ring[i].y > point.y) != (ring[j].y > point.y) &&
                point.x <
                    (ring[j].x - ring[i].x) * (point.y - ring[i].y) / (ring[j].y - ring[i].y) +
                        ring[i].x)
                crossings = !crossings;
        if (crossings)
            inside[rings.polygonOf[r]] = !inside[rings.polygonOf[r]];
    }
    return std::find(inside.begin(), inside.end(), true) != inside.end();
}

/// 1 for the triangles outside the clip area or inside the erase area, by their centroids:
/// the areas' boundaries are chains of TIN edges, so no triangle straddles one.
std::vector<std::uint8_t> outsideArea(const TinMesh& mesh, const io::LineLayer* clip,
                                      const io::LineLayer* erase) {
    std::vector<std::uint8_t> drop(mesh.triangleCount(), 0);
    for (std::size_t t = 0; t < drop.size(); ++t) {
        Point2 centroid{0.0, 0.0};
        for (std::size_t i = 0; i < 3; ++i) {
            centroid.x += mesh.vertices[mesh.triangles[3 * t + i]].x / 3.0;
            centroid.y += mesh.vertices[mesh.triangles[3 * t + i]].y / 3.0;
        }
        drop[t] = (clip != nullptr && !insideAny(*clip, centroid)) ||
                  (erase != nullptr && insideAny(*erase, centroid));
    }
    return drop;
}

} // namespace

ConstrainedBuild addConstraints(TinMesh mesh, const BuildOptions& options,
                                const std::string& crsWkt, BuildReport& report) {
    ConstraintSet constraints;
    std::optional<io::LineLayer> clip;
    std::optional<io::LineLayer> erase;
    {
        TinLocator locator(mesh);
        for (const std::string& source : options.breaklines) {
            io::LineLayer layer = readInCrs(source, "breaklines", options, crsWkt, report);
            if (options.breaklineZ == BreaklineZ::Line)
                checkLineZ(layer, options);
            const std::size_t clipped = addLines(layer, locator, options.breaklineZ, constraints);
            notifyClipped(options, report, source, clipped, layer.lines.size());
            report.clippedBreaklines += clipped;
        }
        report.breaklines = constraints.polylines.size();
        // The areas' boundaries: constrained rings with the surface's z.
        const auto addArea = [&](const std::string& source, std::string_view keyword) {
            io::LineLayer rings = readInCrs(source, keyword, options, crsWkt, report);
            // addLines leaves x and y as they are: the rings still bound the area after it.
            notifyClipped(options, report, source,
                          addLines(rings, locator, BreaklineZ::Surface, constraints),
                          rings.lines.size());
            return rings;
        };
        if (!options.clip.empty())
            clip = addArea(options.clip, "clip");
        if (!options.erase.empty())
            erase = addArea(options.erase, "erase");
    }
    ConstrainedBuild build{insertConstraints(std::move(mesh), constraints), {}};
    report.constraintVertices = build.tin.addedPoints + build.tin.intersections;
    report.constraintCrossings = build.tin.intersections;
    if (clip || erase)
        build.outsideArea =
            outsideArea(build.tin.mesh, clip ? &*clip : nullptr, erase ? &*erase : nullptr);
    return build;
}

} // namespace terratin::detail

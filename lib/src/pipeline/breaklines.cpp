#include "breaklines.hpp"

#include "../parallel/parallel_for.hpp"
#include "constraint_areas.hpp"
#include "gather_inputs.hpp"
#include "terratin/constrain/insert_constraints.hpp"
#include "terratin/crs/reprojection.hpp"
#include "terratin/error.hpp"
#include "terratin/io/ogr_line_reader.hpp"
#include "terratin/pipeline/build_option_table.hpp"
#include "terratin/triangulate/tin_locator.hpp"

#include <algorithm>
#include <cmath>
#include <future>
#include <limits>
#include <optional>
#include <span>
#include <string_view>

namespace terratin::detail {

namespace {

/// The lines (or polygon rings) of one source as read; `keyword` names the option it came from.
io::LineLayer readLayer(const std::string& source, std::string_view keyword,
                        const BuildOptions& options) {
    const std::string option = markOption(keyword);
    return keyword == "breaklines"
               ? io::readOgrLines(source, options.breaklinesLayer, option)
               : io::readOgrPolygons(source, "", option,
                                     keyword == "replace" ? options.replaceZField : std::string());
}

/// `layer`, read from `source` for option `keyword`, in `crsWkt`, with the notices it calls
/// for.
io::LineLayer intoCrs(io::LineLayer layer, const std::string& source, std::string_view keyword,
                      const BuildOptions& options, const std::string& crsWkt, BuildReport& report) {
    const std::string name =
        markOption(keyword) + " '" + source + "' layer '" + layer.layerName + "'";
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
        try {
            for (std::vector<Point3>& line : layer.lines)
                reprojector.transform(std::span<Point3>(line));
        } catch (const CrsError& error) {
            // A layer whose CRS does not match its coordinates: say which layer.
            throw CrsError(name + ": " + error.markedMessage());
        }
    }
    return layer;
}

/// Whether two polylines have the same points in x and y (z may have been filled in).
bool samePlaces(const std::vector<Point3>& a, const std::vector<Point3>& b) {
    return std::equal(a.begin(), a.end(), b.begin(), b.end(),
                      [](const Point3& p, const Point3& q) { return p.x == q.x && p.y == q.y; });
}

void checkLineZ(const io::LineLayer& layer) {
    for (std::size_t i = 0; i < layer.lines.size(); ++i)
        if (std::isnan(layer.lines[i].front().z))
            throw InvalidInputError("Breaklines: " + markOption("breakline_z") + " line: feature " +
                                    std::to_string(layer.featureIds[i]) + " of '" + layer.source +
                                    "' has no z");
}

/// Gives the points of `layer` that take the surface's z (all under BreaklineZ::Surface, those
/// without one under Auto) `dem`'s bilinear elevation, NaN where it has none or there is no
/// `dem`; on up to `threads` threads (0: all hardware threads).
void takeSurfaceZ(io::LineLayer& layer, const HeightGrid* dem, BreaklineZ zFrom, unsigned threads) {
    if (zFrom == BreaklineZ::Line)
        return;
    const auto giveZ = [&](std::vector<Point3>& line) {
        for (Point3& point : line)
            if (zFrom == BreaklineZ::Surface || std::isnan(point.z))
                point.z = dem != nullptr ? bilinearElevation(*dem, {point.x, point.y})
                                         : std::numeric_limits<double>::quiet_NaN();
    };
    // A few lines per chunk, the chunks taken in turn: the lines' lengths differ.
    constexpr std::size_t kLinesPerChunk = 16;
    forChunksInTurn(layer.lines.size(), threads, kLinesPerChunk,
                    [&](std::size_t begin, std::size_t end) {
                        for (std::size_t i = begin; i < end; ++i)
                            giveZ(layer.lines[i]);
                    });
}

/// Adds `part` to `constraints`, and to `openEnds` (when given) its ends cut at the hull.
void addPart(TinLocator::LocatedPolyline part, ConstraintSet& constraints,
             std::vector<OpenRingEnd>* openEnds) {
    const std::size_t chain = constraints.polylines.size();
    if (openEnds != nullptr) {
        if (part.enteredFrom)
            openEnds->push_back({chain, false, *part.enteredFrom});
        if (part.leftTowards)
            openEnds->push_back({chain, true, *part.leftTowards});
    }
    constraints.polylines.push_back(std::move(part.points));
    constraints.polylineTriangles.push_back(std::move(part.triangles));
}

/// The lines of `layer` clipped to the hull into `constraints`; an area's rings note where they
/// were cut in `openEnds`. Returns how many lines were clipped.
std::size_t addLines(io::LineLayer& layer, const TinLocator& locator, unsigned threads,
                     ConstraintSet& constraints, std::vector<OpenRingEnd>* openEnds = nullptr) {
    // Inside the hull after clipping, with the TIN's z where a point still has none; the
    // triangles found spare insertConstraints a second search, and a point not located is
    // found from the one before it.
    static_assert(TinLocator::kUnlocated == kFromPreviousPoint);
    std::vector<std::vector<TinLocator::LocatedPolyline>> located =
        locator.clipToSurface(layer.lines, threads);
    std::size_t clipped = 0;
    for (std::size_t i = 0; i < located.size(); ++i) {
        std::vector<TinLocator::LocatedPolyline>& parts = located[i];
        clipped += parts.size() != 1 || !samePlaces(parts.front().points, layer.lines[i]) ? 1 : 0;
        for (TinLocator::LocatedPolyline& part : parts)
            addPart(std::move(part), constraints, openEnds);
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

/// The mean spacing of `mesh`'s vertices: the side of a square of its bounding box's area
/// shared among them.
double meanSpacing(const TinMesh& mesh) {
    Point2 low{mesh.vertices[0].x, mesh.vertices[0].y};
    Point2 high = low;
    for (const Point3& p : mesh.vertices) {
        low = {std::min(low.x, p.x), std::min(low.y, p.y)};
        high = {std::max(high.x, p.x), std::max(high.y, p.y)};
    }
    return std::sqrt((high.x - low.x) * (high.y - low.y) / static_cast<double>(mesh.vertexCount()));
}

/// Each replace polygon's level: its --replace-z-field value, or the lowest surface elevation on
/// its boundary (sampled at a quarter of the vertices' mean spacing).
std::vector<double> replaceLevels(const io::LineLayer& rings, const PolygonSet& polygons,
                                  TinLocator& locator, const TinMesh& mesh,
                                  const BuildOptions& options) {
    if (!options.replaceZField.empty())
        return rings.polygonValues;
    std::vector<double> levels = lowestLevelsOnBoundary(polygons, locator, meanSpacing(mesh) / 4);
    for (std::size_t r = 0; r < rings.lines.size(); ++r)
        if (std::isnan(levels[rings.polygonOf[r]]))
            throw InvalidInputError(
                "Build: " + markOption("replace") + " '" + rings.source + "' feature " +
                std::to_string(rings.featureIds[r]) +
                ": its boundary lies outside the data; give its elevation with " +
                markOption("replace_z_field"));
    return levels;
}

/// The replace rings as constraints at their polygon's level, clipped to the hull, their cut
/// ends noted in `openEnds`; returns the level of each polyline added.
std::vector<double> addFlatRings(io::LineLayer& rings, const std::vector<double>& levels,
                                 TinLocator& locator, ConstraintSet& constraints,
                                 std::vector<OpenRingEnd>& openEnds) {
    std::vector<double> ringLevels;
    for (std::size_t r = 0; r < rings.lines.size(); ++r) {
        for (Point3& point : rings.lines[r])
            point.z = levels[rings.polygonOf[r]];
        for (TinLocator::LocatedPolyline& part : locator.clipToSurface(rings.lines[r])) {
            addPart(std::move(part), constraints, &openEnds);
            ringLevels.push_back(levels[rings.polygonOf[r]]);
        }
    }
    return ringLevels;
}

/// Every point of `polylines` inside a replace polygon gets that polygon's level.
void flattenPointsInside(std::span<std::vector<Point3>> polylines, const PolygonSet& replace,
                         const std::vector<double>& levels) {
    for (std::vector<Point3>& line : polylines)
        for (Point3& point : line)
            if (const std::optional<std::size_t> k = replace.polygonHolding({point.x, point.y}))
                point.z = levels[*k];
}

/// The replace polygons and each one's level.
struct ReplaceAreas {
    PolygonSet polygons;
    std::vector<double> levels; // per polygon
};

/// The replace rings (build.replace) as constraints at their polygon's level (addFlatRings);
/// nullopt without replace areas. Fills build.ringLevels and report.replacePolygons.
std::optional<ReplaceAreas> addReplaceRings(ConstrainedBuild& build, TinLocator& locator,
                                            const TinMesh& mesh, const BuildOptions& options,
                                            ConstraintSet& constraints, BuildReport& report) {
    if (!build.replace)
        return std::nullopt;
    ReplaceAreas areas{PolygonSet(*build.replace), {}};
    areas.levels = replaceLevels(*build.replace, areas.polygons, locator, mesh, options);
    build.ringLevels =
        addFlatRings(*build.replace, areas.levels, locator, constraints, build.openRingEnds);
    report.replacePolygons = areas.levels.size();
    return areas;
}

/// The lines of every breakline source clipped to the hull into `constraints`, with a notice
/// for each source some were clipped from. Fills report.breaklines and clippedBreaklines.
void addBreaklines(std::vector<io::LineLayer>& breaklines, const TinLocator& locator,
                   const BuildOptions& options, ConstraintSet& constraints, BuildReport& report) {
    const std::size_t first = constraints.polylines.size();
    for (io::LineLayer& layer : breaklines) {
        const std::size_t clipped =
            addLines(layer, locator, options.triangulation.threads, constraints);
        notifyClipped(options, report, layer.source, clipped, layer.lines.size());
        report.clippedBreaklines += clipped;
    }
    report.breaklines = constraints.polylines.size() - first;
}

/// The clip and erase areas' boundaries: constrained rings with the surface's z, their cut ends
/// noted in build.openRingEnds. addLines leaves x and y as they are: the rings still bound the
/// areas after it.
void addAreaRings(ConstrainedBuild& build, const TinLocator& locator, const BuildOptions& options,
                  ConstraintSet& constraints, BuildReport& report) {
    for (std::optional<io::LineLayer>* area : {&build.clip, &build.erase})
        if (*area)
            notifyClipped(options, report, (*area)->source,
                          addLines(**area, locator, options.triangulation.threads, constraints,
                                   &build.openRingEnds),
                          (*area)->lines.size());
}

/// `mesh` with the points inside the replace areas left out and those on its hull at their
/// area's level (flattenAreas). Fills report.replacedPoints.
TinMesh leaveOutReplacedPoints(TinMesh mesh, const ReplaceAreas& areas,
                               const TriangulationOptions& options, ConstraintSet& constraints,
                               BuildReport& report) {
    std::size_t removed = 0;
    mesh = flattenAreas(std::move(mesh), areas.polygons, areas.levels, options, removed);
    if (removed > 0)
        constraints.polylineTriangles.clear(); // they were the old mesh's
    report.replacedPoints = removed;
    return mesh;
}

/// build.outsideArea for build.tin, from its clip and erase areas (at least one given).
std::vector<std::uint8_t> trianglesOutsideAreas(const ConstrainedBuild& build) {
    const std::optional<PolygonSet> clipArea =
        build.clip ? std::optional<PolygonSet>(*build.clip) : std::nullopt;
    const std::optional<PolygonSet> eraseArea =
        build.erase ? std::optional<PolygonSet>(*build.erase) : std::nullopt;
    return trianglesOutsideArea(build.tin, build.openRingEnds, clipArea ? &*clipArea : nullptr,
                                eraseArea ? &*eraseArea : nullptr);
}

} // namespace

void flattenReplaceRings(ConstrainedBuild& build) {
    for (std::size_t r = 0; r < build.ringLevels.size(); ++r)
        for (const std::uint32_t v : build.tin.chains[r])
            build.tin.mesh.vertices[v].z = build.ringLevels[r];
}

template <class Visit> void ConstraintSources::forEachLayer(Visit&& visit) const {
    for (const std::optional<io::LineLayer>* area : {&clip, &erase, &replace})
        if (*area)
            visit(**area);
    for (const io::LineLayer& layer : breaklines)
        visit(layer);
}

std::size_t ConstraintSources::spareVertices() const {
    std::size_t vertices = 0;
    forEachLayer([&](const io::LineLayer& layer) {
        for (const std::vector<Point3>& line : layer.lines)
            vertices += line.size();
    });
    return 2 * vertices;
}

std::size_t ConstraintSources::lineCount() const {
    std::size_t lines = 0;
    forEachLayer([&](const io::LineLayer& layer) { lines += layer.lines.size(); });
    return lines;
}

ConstraintLayers readConstraintLayers(const BuildOptions& options) {
    ConstraintLayers layers;
    if (!options.clip.empty())
        layers.clip = readLayer(options.clip, "clip", options);
    if (!options.erase.empty())
        layers.erase = readLayer(options.erase, "erase", options);
    if (!options.replace.empty())
        layers.replace = readLayer(options.replace, "replace", options);
    for (const std::string& source : options.breaklines)
        layers.breaklines.push_back(readLayer(source, "breaklines", options));
    return layers;
}

std::future<ConstraintLayers> startReadingConstraintLayers(const BuildOptions& options) {
    return std::async(std::launch::async, [&options] { return readConstraintLayers(options); });
}

ConstraintSources readConstraintSources(ConstraintLayers layers, const BuildOptions& options,
                                        const std::string& crsWkt, const HeightGrid* dem,
                                        BuildReport& report) {
    ConstraintSources sources;
    if (layers.clip)
        sources.clip =
            intoCrs(std::move(*layers.clip), options.clip, "clip", options, crsWkt, report);
    if (layers.erase)
        sources.erase =
            intoCrs(std::move(*layers.erase), options.erase, "erase", options, crsWkt, report);
    if (layers.replace)
        sources.replace = intoCrs(std::move(*layers.replace), options.replace, "replace", options,
                                  crsWkt, report);
    for (std::optional<io::LineLayer>* area : {&sources.clip, &sources.erase})
        if (*area)
            takeSurfaceZ(**area, dem, BreaklineZ::Surface, options.triangulation.threads);
    for (std::size_t i = 0; i < layers.breaklines.size(); ++i) {
        io::LineLayer& layer = sources.breaklines.emplace_back(
            intoCrs(std::move(layers.breaklines[i]), options.breaklines[i], "breaklines", options,
                    crsWkt, report));
        if (options.breaklineZ == BreaklineZ::Line)
            checkLineZ(layer);
        takeSurfaceZ(layer, dem, options.breaklineZ, options.triangulation.threads);
    }
    return sources;
}

ConstrainedBuild addConstraints(TinMesh mesh, const BuildOptions& options, BuildReport& report,
                                ConstraintSources sources, const ProgressCallback& progress) {
    ConstraintSet constraints;
    constraints.threads = threadsOrAll(options.triangulation.threads);
    const std::size_t lineCount = sources.lineCount();
    ConstrainedBuild build;
    build.clip = std::move(sources.clip);
    build.erase = std::move(sources.erase);
    build.replace = std::move(sources.replace);
    std::optional<ReplaceAreas> replaceAreas;
    {
        // The inputs' surface, before any point is left out: triangulate()'s or the refiner's
        // mesh (with its triangles over holes), which covers its convex hull; its locator
        // serves a jump to each line's first point and walks along the lines.
        TinLocator locator(mesh, {.threads = options.triangulation.threads,
                                  .coversConvexHull = true,
                                  .farQueries = lineCount});
        // Replace rings go in first, so that where a line crosses one the new vertex takes the
        // ring's level.
        replaceAreas = addReplaceRings(build, locator, mesh, options, constraints, report);
        const std::size_t firstBreakline = constraints.polylines.size();
        addBreaklines(sources.breaklines, locator, options, constraints, report);
        addAreaRings(build, locator, options, constraints, report);
        if (replaceAreas)
            flattenPointsInside(std::span(constraints.polylines).subspan(firstBreakline),
                                replaceAreas->polygons, replaceAreas->levels);
    }
    if (replaceAreas)
        mesh = leaveOutReplacedPoints(std::move(mesh), *replaceAreas, options.triangulation,
                                      constraints, report);
    build.tin = insertConstraints(std::move(mesh), constraints, progress);
    flattenReplaceRings(build);
    report.constraintVertices = build.tin.addedPoints + build.tin.intersections;
    report.constraintCrossings = build.tin.intersections;
    if (build.clip || build.erase)
        build.outsideArea = trianglesOutsideAreas(build);
    return build;
}

} // namespace terratin::detail

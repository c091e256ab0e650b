#include "zoned_insertion.hpp"

#include "../parallel/parallel_for.hpp"
#include "../parallel/watched_threads.hpp"
#include "terratin/error.hpp"

#include <algorithm>
#include <atomic>
#include <bit>
#include <memory>
#include <utility>

namespace terratin::detail {

namespace {

/// One zone of a round: its band, the polylines it goes on with, its inserter and what it
/// refused.
struct ZoneWork {
    Zone zone;
    std::vector<PolylineProgress> todo;
    std::size_t points = 0;
    std::size_t segments = 0;
    std::unique_ptr<ConstraintInserter> inserter;
    std::vector<PolylineProgress> refused;
};

/// Where a polyline goes on: its next point, or the start of its next segment.
const Point3& resumePoint(const ConstraintSet& constraints, const PolylineProgress& progress) {
    const std::vector<Point3>& polyline = constraints.polylines[progress.polyline];
    return progress.nextPoint < polyline.size() ? polyline[progress.nextPoint]
                                                : polyline[progress.nextSegment - 1];
}

/// `zones` bands of x (or of y, `alongY`) holding about as many of `todo` each, by where they
/// go on.
std::vector<ZoneWork> zoneBands(const ConstraintSet& constraints,
                                std::vector<PolylineProgress> todo, unsigned zones, bool alongY) {
    const auto coordinate = [&](const PolylineProgress& progress) {
        const Point3& p = resumePoint(constraints, progress);
        return alongY ? p.y : p.x;
    };
    std::vector<double> at;
    for (const PolylineProgress& progress : todo)
        at.push_back(coordinate(progress));
    std::vector<ZoneWork> works(zones);
    const std::vector<Zone> bands = bandsHoldingAsMany(std::move(at), zones, alongY);
    for (unsigned z = 0; z < zones; ++z)
        works[z].zone = bands[z];
    for (PolylineProgress& progress : todo) {
        const double c = coordinate(progress);
        ZoneWork& work = *std::find_if(works.begin(), works.end(),
                                       [&](const ZoneWork& w) { return c < w.zone.high; });
        const std::size_t points = constraints.polylines[progress.polyline].size();
        work.points += points - progress.nextPoint;
        work.segments += points - progress.nextSegment;
        work.todo.push_back(std::move(progress));
    }
    return works;
}

/// Where each point's search starts in a zone: its triangle in polylineTriangles when a corner
/// of it now lies in the zone (a triangle the zone may read, however it changes), else (and for
/// kFromPreviousPoint) the previous point's vertex.
std::vector<std::uint32_t> zoneStarts(const CdtMesh& mesh, const ConstraintSet& constraints,
                                      std::size_t k, const Zone& zone) {
    const auto inZone = [&](std::uint32_t v) { return zone.holds(mesh.vertex(v)); };
    std::vector<std::uint32_t> starts;
    for (const std::uint32_t t : constraints.polylineTriangles[k]) {
        const bool readable =
            t != kFromPreviousPoint &&
            (inZone(mesh.from(3 * std::size_t{t})) || inZone(mesh.from(3 * std::size_t{t} + 1)) ||
             inZone(mesh.from(3 * std::size_t{t} + 2)));
        starts.push_back(readable ? t : kFromPreviousPoint);
    }
    return starts;
}

/// Goes on with a zone's polylines in order, each as far as the zone allows.
void runZone(ZoneWork& work, const ConstraintSet& constraints,
             const std::vector<std::vector<std::uint32_t>>& starts,
             const std::vector<std::uint32_t>& firstOwner,
             std::vector<std::vector<std::uint32_t>>& vertices) {
    for (PolylineProgress& progress : work.todo) {
        const std::size_t k = progress.polyline;
        if (progress.nextPoint == 0 && starts[k].front() == kFromPreviousPoint) {
            work.refused.push_back(std::move(progress)); // no safe place to start from
            continue;
        }
        try {
            insertPolyline(*work.inserter, constraints, vertices[k], firstOwner[k], progress,
                           starts[k]);
        } catch (const ZoneRefusal&) {
            progress.pieces = work.inserter->takePieces();
            work.refused.push_back(std::move(progress));
        }
    }
}

/// Slots for a zone of `vertices` and `triangles`: the front of an earlier zone's unused slots
/// (`result`'s) where both have the room, else new ones at the end of the mesh. The second
/// round's zones then fill the first round's leftovers, and compact has fewer holes to close
/// up, each a triangle or a vertex moved and its neighbours relinked.
std::pair<SlotRange, SlotRange> takeSlots(ConstraintInserter& inserter, std::size_t vertices,
                                          std::size_t triangles, ZonedInsertion& result) {
    for (std::size_t i = 0; i < result.unusedVertices.size(); ++i) {
        SlotRange& vertexSlots = result.unusedVertices[i];
        SlotRange& triangleSlots = result.unusedTriangles[i];
        if (vertexSlots.end - vertexSlots.next < vertices ||
            triangleSlots.end - triangleSlots.next < triangles)
            continue;
        const SlotRange zoneVertices{vertexSlots.next, vertexSlots.next + vertices};
        const SlotRange zoneTriangles{triangleSlots.next, triangleSlots.next + triangles};
        vertexSlots.next = zoneVertices.end;
        triangleSlots.next = zoneTriangles.end;
        return {zoneVertices, zoneTriangles};
    }
    return inserter.appendSlots(vertices, triangles);
}

/// One round: `todo` in `zones` bands of x or of y on up to `threads` threads; the flips held
/// back at the bands' edges made after. Returns what the zones refused, in polyline order.
/// The zones' slots come from those `result` holds unused where they fit (takeSlots); the
/// slots the zones leave unused go to `result`.
std::vector<PolylineProgress>
runRound(ConstraintInserter& inserter, const ConstraintSet& constraints,
         std::vector<PolylineProgress> todo, unsigned zones, bool alongY, unsigned threads,
         const std::vector<std::uint32_t>& firstOwner,
         std::vector<std::vector<std::uint32_t>>& vertices, ZonedInsertion& result,
         const std::function<bool()>& keepGoing) {
    if (todo.empty())
        return {};
    std::atomic<bool> stop{false};
    std::vector<ZoneWork> works = zoneBands(constraints, std::move(todo), zones, alongY);
    std::vector<std::vector<std::uint32_t>> starts(constraints.polylines.size());
    for (ZoneWork& work : works) {
        if (work.todo.empty())
            continue;
        for (const PolylineProgress& progress : work.todo)
            starts[progress.polyline] =
                zoneStarts(inserter.mesh(), constraints, progress.polyline, work.zone);
        // Room for every point and a crossing on every fourth segment (a polyline the first
        // round refused has most of its points in and its segments still to go); a zone that
        // runs out refuses the rest.
        const std::size_t room = work.points + work.segments / 4 + 64;
        const auto [vertexSlots, triangleSlots] = takeSlots(inserter, room, 2 * room, result);
        work.inserter = std::make_unique<ConstraintInserter>(inserter, work.zone, vertexSlots,
                                                             triangleSlots, work.segments);
        work.inserter->setPoll(InsertionPoll([&stop] {
            if (stop.load(std::memory_order_relaxed))
                throw Cancelled("insertConstraints: cancelled");
        }));
    }
    // The zones on threads of their own; this one watches the progress callback meanwhile.
    const unsigned workers = std::clamp(threads, 1U, zones);
    const bool finished = runWatched(
        workers,
        [&](unsigned worker) {
            for (std::size_t z = worker; z < works.size(); z += workers)
                runZone(works[z], constraints, starts, firstOwner, vertices);
        },
        [&keepGoing] { return !keepGoing || keepGoing(); },
        [&stop] { stop.store(true, std::memory_order_relaxed); });
    if (!finished)
        throw Cancelled("insertConstraints: cancelled");

    std::vector<PolylineProgress> refused;
    for (ZoneWork& work : works) {
        if (!work.inserter)
            continue;
        inserter.absorb(*work.inserter);
        result.unusedVertices.push_back(work.inserter->vertexSlots());
        result.unusedTriangles.push_back(work.inserter->triangleSlots());
        for (PolylineProgress& progress : work.refused)
            refused.push_back(std::move(progress));
    }
    std::sort(refused.begin(), refused.end(),
              [](const PolylineProgress& a, const PolylineProgress& b) {
                  return a.polyline < b.polyline;
              });
    return refused;
}

} // namespace

unsigned zoneCount(const ConstraintSet& constraints) {
    if (constraints.zones != 0)
        return constraints.zones;
    std::size_t points = 0;
    for (const std::vector<Point3>& polyline : constraints.polylines)
        points += polyline.size();
    return static_cast<unsigned>(
        std::clamp<std::size_t>(std::bit_floor(points / kPointsPerZone), 1, kMaxZones));
}

ZonedInsertion insertInZones(ConstraintInserter& inserter, const ConstraintSet& constraints,
                             unsigned zones, unsigned threads,
                             const std::vector<std::uint32_t>& firstOwner,
                             std::vector<std::vector<std::uint32_t>>& vertices,
                             const std::function<bool()>& keepGoing) {
    std::vector<PolylineProgress> todo;
    for (std::size_t k = 0; k < constraints.polylines.size(); ++k)
        if (!constraints.polylines[k].empty()) {
            todo.emplace_back();
            todo.back().polyline = k;
        }
    ZonedInsertion result;
    // Bands of x, then, for what stopped at their edges (polylines near a line x = c), bands
    // of y.
    std::vector<PolylineProgress> refused =
        runRound(inserter, constraints, std::move(todo), zones, false, threads, firstOwner,
                 vertices, result, keepGoing);
    result.refused = runRound(inserter, constraints, std::move(refused), zones, true, threads,
                              firstOwner, vertices, result, keepGoing);
    return result;
}

} // namespace terratin::detail

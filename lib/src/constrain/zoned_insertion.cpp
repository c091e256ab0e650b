#include "zoned_insertion.hpp"

#include "../triangulate/parallel_for.hpp"

#include <algorithm>
#include <bit>
#include <limits>
#include <memory>

namespace terratin::detail {

namespace {

/// One zone: its band, its polylines, its inserter and what it refused.
struct ZoneWork {
    Zone zone;
    std::vector<std::size_t> polylines;
    std::size_t points = 0;
    std::size_t segments = 0;
    std::unique_ptr<ConstraintInserter> inserter;
    std::vector<PolylineProgress> refused;
};

/// `zones` bands holding about as many polylines each, by the x of their first points.
std::vector<ZoneWork> zoneBands(const ConstraintSet& constraints, unsigned zones) {
    std::vector<double> firstX;
    for (const std::vector<Point3>& polyline : constraints.polylines)
        if (!polyline.empty())
            firstX.push_back(polyline.front().x);
    std::sort(firstX.begin(), firstX.end());
    std::vector<ZoneWork> works(zones);
    double low = -std::numeric_limits<double>::infinity();
    for (unsigned z = 0; z < zones; ++z) {
        const double high = z + 1 == zones || firstX.empty()
                                ? std::numeric_limits<double>::infinity()
                                : firstX[(z + 1) * firstX.size() / zones];
        works[z].zone = {low, high};
        low = high;
    }
    for (std::size_t k = 0; k < constraints.polylines.size(); ++k) {
        const std::vector<Point3>& polyline = constraints.polylines[k];
        if (polyline.empty())
            continue;
        ZoneWork& work = *std::find_if(works.begin(), works.end(), [&](const ZoneWork& w) {
            return polyline.front().x < w.zone.high;
        });
        work.polylines.push_back(k);
        work.points += polyline.size();
        work.segments += polyline.size() - 1;
    }
    return works;
}

/// Where each point's search starts in a zone: its triangle in polylineTriangles when a corner
/// of it lies in the zone (a triangle the zone may read, however it changes), else the previous
/// point's vertex. The mesh must be as polylineTriangles describe it.
std::vector<std::uint32_t> zoneStarts(const CdtMesh& mesh, const ConstraintSet& constraints,
                                      std::size_t k, const Zone& zone) {
    const auto inZone = [&](std::uint32_t v) {
        return mesh.vertex(v).x >= zone.low && mesh.vertex(v).x < zone.high;
    };
    std::vector<std::uint32_t> starts;
    for (const std::uint32_t t : constraints.polylineTriangles[k]) {
        const bool readable = inZone(mesh.from(3 * std::size_t{t})) ||
                              inZone(mesh.from(3 * std::size_t{t} + 1)) ||
                              inZone(mesh.from(3 * std::size_t{t} + 2));
        starts.push_back(readable ? t : kFromPreviousPoint);
    }
    return starts;
}

/// Inserts a zone's polylines in order, each as far as the zone allows.
void runZone(ZoneWork& work, const ConstraintSet& constraints,
             const std::vector<std::vector<std::uint32_t>>& starts,
             const std::vector<std::uint32_t>& firstOwner,
             std::vector<std::vector<std::uint32_t>>& vertices) {
    for (const std::size_t k : work.polylines) {
        PolylineProgress progress;
        progress.polyline = k;
        if (starts[k].front() == kFromPreviousPoint) {
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
                             std::vector<std::vector<std::uint32_t>>& vertices) {
    std::vector<ZoneWork> works = zoneBands(constraints, zones);
    std::vector<std::vector<std::uint32_t>> starts(constraints.polylines.size());
    for (ZoneWork& work : works) {
        for (const std::size_t k : work.polylines)
            starts[k] = zoneStarts(inserter.mesh(), constraints, k, work.zone);
        // Room for every point and a quarter as many crossings; a zone that runs out refuses
        // the rest.
        const std::size_t room = work.points + work.points / 4 + 64;
        const auto [vertexSlots, triangleSlots] = inserter.appendSlots(room, 2 * room);
        work.inserter = std::make_unique<ConstraintInserter>(inserter, work.zone, vertexSlots,
                                                             triangleSlots, work.segments);
    }
    const unsigned workers = std::clamp(threads, 1U, zones);
    runOnThreads(workers, [&](unsigned worker) {
        for (std::size_t z = worker; z < works.size(); z += workers)
            runZone(works[z], constraints, starts, firstOwner, vertices);
    });

    ZonedInsertion result;
    for (ZoneWork& work : works) {
        inserter.absorb(*work.inserter);
        result.unusedVertices.push_back(work.inserter->vertexSlots());
        result.unusedTriangles.push_back(work.inserter->triangleSlots());
        for (PolylineProgress& progress : work.refused)
            result.refused.push_back(std::move(progress));
    }
    std::sort(result.refused.begin(), result.refused.end(),
              [](const PolylineProgress& a, const PolylineProgress& b) {
                  return a.polyline < b.polyline;
              });
    return result;
}

} // namespace terratin::detail

#include "terratin/constrain/insert_constraints.hpp"

#include "constraint_inserter.hpp"
#include "polyline_insertion.hpp"
#include "terratin/error.hpp"
#include "zoned_insertion.hpp"

#include <cmath>
#include <functional>
#include <limits>
#include <string>
#include <string_view>

namespace terratin {

namespace {

constexpr std::string_view kInsertingConstraints = "inserting constraints";
constexpr const char* kCancelled = "insertConstraints: cancelled";

void checkPolylineTriangles(const TinMesh& mesh, const ConstraintSet& constraints) {
    const std::vector<std::vector<std::uint32_t>>& triangles = constraints.polylineTriangles;
    if (triangles.empty())
        return;
    if (triangles.size() != constraints.polylines.size())
        throw InvalidInputError("insertConstraints: triangles given for " +
                                std::to_string(triangles.size()) + " polylines of " +
                                std::to_string(constraints.polylines.size()));
    for (std::size_t k = 0; k < triangles.size(); ++k) {
        if (triangles[k].size() != constraints.polylines[k].size())
            throw InvalidInputError("insertConstraints: polyline " + std::to_string(k) + " has " +
                                    std::to_string(constraints.polylines[k].size()) +
                                    " points and " + std::to_string(triangles[k].size()) +
                                    " triangles");
        for (const std::uint32_t t : triangles[k])
            if (t >= mesh.triangleCount() && t != kFromPreviousPoint)
                throw InvalidInputError("insertConstraints: polyline " + std::to_string(k) +
                                        " names triangle " + std::to_string(t) + " of a mesh of " +
                                        std::to_string(mesh.triangleCount()) + " triangles");
    }
}

// Returns the number of segments in all.
std::size_t checkConstraints(const TinMesh& mesh, const ConstraintSet& constraints) {
    const std::size_t vertexCount = mesh.vertexCount();
    for (std::size_t k = 0; k < constraints.segments.size(); ++k)
        for (const std::uint32_t v : constraints.segments[k])
            if (v >= vertexCount)
                throw InvalidInputError("insertConstraints: segment " + std::to_string(k) +
                                        " names vertex " + std::to_string(v) + " of a mesh of " +
                                        std::to_string(vertexCount) + " vertices");
    for (std::size_t k = 0; k < constraints.polylines.size(); ++k)
        for (std::size_t j = 0; j < constraints.polylines[k].size(); ++j) {
            const Point3& p = constraints.polylines[k][j];
            if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
                throw InvalidInputError("insertConstraints: polyline " + std::to_string(k) +
                                        ", point " + std::to_string(j) + " is not finite");
        }
    checkPolylineTriangles(mesh, constraints);
    std::size_t segments = constraints.segments.size();
    for (const std::vector<Point3>& polyline : constraints.polylines)
        segments += polyline.empty() ? 0 : polyline.size() - 1;
    if (segments >= std::numeric_limits<std::uint32_t>::max() - 1)
        throw InvalidInputError("insertConstraints: too many segments (" +
                                std::to_string(segments) + ")");
    const bool any = !constraints.segments.empty() || !constraints.polylines.empty();
    if (any && mesh.triangleCount() == 0)
        throw InvalidInputError("insertConstraints: the mesh has no triangles");
    return segments;
}

/// The owner number of each polyline's first segment: the index segments own 0 to
/// segments - 1, then the polylines' segments follow in order. `owners` receives the count.
std::vector<std::uint32_t> firstOwners(const ConstraintSet& constraints, std::size_t& owners) {
    std::vector<std::uint32_t> firstOwner;
    owners = constraints.segments.size();
    for (const std::vector<Point3>& polyline : constraints.polylines) {
        firstOwner.push_back(static_cast<std::uint32_t>(owners));
        owners += polyline.empty() ? 0 : polyline.size() - 1;
    }
    return firstOwner;
}

/// The polylines inserted: in zones on the threads where they are many and come with their
/// triangles in the mesh as given (no index segment has changed it), then on this thread what
/// they refused, or every polyline. polylines[k] receives polyline k's vertices.
void insertPolylines(detail::ConstraintInserter& inserter, const ConstraintSet& constraints,
                     const std::vector<std::uint32_t>& firstOwner,
                     std::vector<std::vector<std::uint32_t>>& polylines,
                     const std::function<bool()>& keepGoing) {
    const unsigned zones = constraints.segments.empty() && !constraints.polylineTriangles.empty()
                               ? detail::zoneCount(constraints)
                               : 1;
    detail::ZonedInsertion zoned;
    if (zones > 1) {
        zoned = detail::insertInZones(inserter, constraints, zones, constraints.threads, firstOwner,
                                      polylines, keepGoing);
    } else {
        zoned.refused.resize(constraints.polylines.size());
        for (std::size_t k = 0; k < constraints.polylines.size(); ++k)
            zoned.refused[k].polyline = k;
    }
    for (detail::PolylineProgress& left : zoned.refused)
        detail::insertPolyline(inserter, constraints, polylines[left.polyline],
                               firstOwner[left.polyline], left);
    if (zones > 1)
        inserter.compact(zoned.unusedVertices, zoned.unusedTriangles, polylines);
}

/// Each input segment's chain, then each polyline's (its segments' chains joined), into `tin`.
void collectChains(const detail::ConstraintInserter& inserter, const ConstraintSet& constraints,
                   const std::vector<std::vector<std::uint32_t>>& polylines, ConstrainedTin& tin) {
    for (std::size_t s = 0; s < constraints.segments.size(); ++s)
        tin.chains.push_back(inserter.chainOf(static_cast<std::uint32_t>(s)));
    std::size_t owner = constraints.segments.size();
    for (const std::vector<std::uint32_t>& polyline : polylines) {
        std::vector<std::uint32_t> chain;
        if (!polyline.empty())
            chain.push_back(polyline.front());
        for (std::size_t j = 1; j < polyline.size(); ++j, ++owner)
            inserter.appendChainAfterFirst(static_cast<std::uint32_t>(owner), chain);
        tin.chains.push_back(std::move(chain));
    }
}

} // namespace

ConstrainedTin insertConstraints(TinMesh mesh, const ConstraintSet& constraints,
                                 const ProgressCallback& progress) {
    const std::size_t segmentCount = checkConstraints(mesh, constraints);
    detail::ConstraintInserter inserter(std::move(mesh), segmentCount);
    const auto keepGoing = [&] {
        return !progress || progress(inserter.fractionInserted(), kInsertingConstraints);
    };
    if (progress)
        inserter.setPoll(detail::InsertionPoll([&] {
            if (!keepGoing())
                throw Cancelled(kCancelled);
        }));

    // The index segments, then each polyline: its points (a point on a constrained edge splits
    // it), then its segments, while the mesh around them is still in cache. Every input segment
    // is numbered as the owner of the edges it becomes.
    const std::vector<std::array<std::uint32_t, 2>>& segments = constraints.segments;
    for (std::size_t s = 0; s < segments.size(); ++s)
        inserter.insertSegment(segments[s][0], segments[s][1], static_cast<std::uint32_t>(s));
    std::size_t owners = 0;
    const std::vector<std::uint32_t> firstOwner = firstOwners(constraints, owners);
    inserter.prepareChains(owners);
    std::vector<std::vector<std::uint32_t>> polylines(constraints.polylines.size());
    insertPolylines(inserter, constraints, firstOwner, polylines, keepGoing);

    ConstrainedTin tin;
    collectChains(inserter, constraints, polylines, tin);
    inserter.finish(tin);
    return tin;
}

} // namespace terratin

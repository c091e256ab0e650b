#pragma once
/// @file
/// A history-free Delaunay triangulation built by Bowyer-Watson insertion with walking point
/// location: the core of the sequential walk and of the strip method (strip_insertion.hpp).
///
/// The DAG of dag_triangulator.hpp keeps every triangle ever made (about 9 nodes per point);
/// here the triangles of a point's cavity are rewritten in place by the triangles around it,
/// so the live mesh (2 triangles of 24 bytes per point) is all the memory there is, and with
/// a spatially sorted insertion order the walk from the previous point is a few steps in
/// cache.
///
/// The mesh covers the whole plane: every convex hull edge has a ghost triangle whose third
/// corner is a vertex at infinity (kGhostVertex, always corner 2). A point outside the hull
/// conflicts with the ghosts of the hull edges it sees, so points may come in any order and no
/// auxiliary triangle or symbolic point is needed. Predicates are exact: a real triangle is in
/// conflict when the point is inside its circumcircle, cocircular points decided by
/// predicates::incircleTieBroken, so the result is exactly Delaunay and the same triangulation
/// the other methods build.
///
/// Concurrency (the strip method): every triangle has an owner, the strip holding all its
/// finite corners, or kSharedOwner. An insertion restricted to one owner reads and rewrites
/// only triangles of that owner; a shared triangle next to its cavity is read (corners, never
/// rewritten while threads run) and gets one link rewritten, the one facing that cavity.
/// Neighbours across an edge share its corners, so a triangle of one strip never touches
/// another strip's triangles and insertions in different strips never race. An insertion that
/// would walk into or conflict with a shared triangle is refused (the point is deferred).
///
/// Merged strips: at level L, strips s with the same s >> L form one group, and an insertion
/// restricted to group g may touch the triangles whose finite corners all lie in g, shared
/// ones included. The argument above holds for groups as for strips, so insertions in
/// different groups of one level never race either. Triangles keep their strip labels.
///
/// Why the refiner has its own core (RefineMesh, lib/src/refine/refine_mesh.hpp) though both
/// are restricted Bowyer-Watson insertions: its triangles carry a version per slot (its lazy
/// candidates), a range of strips (its tasks are strips and pairs of strips) and an
/// insertion cap, and its vertices their pixel; it starts from a convex hull, without ghosts.
/// Here the points come in any order and a triangle has one owner; each field of the other
/// would cost memory per triangle that this method never reads.

#include "../huge_pages.hpp"
#include "terratin/geometry/point.hpp"
#include "terratin/triangulate/tin_mesh.hpp"

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

namespace terratin::detail {

using CavityVertex = std::uint32_t;
using CavityTriangleId = std::uint32_t;
/// A neighbour: triangle * 4 + the corner of that triangle opposite the shared edge.
using CavityLink = std::uint32_t;

/// The vertex at infinity: corner 2 of every ghost triangle.
inline constexpr CavityVertex kGhostVertex = 0xFFFFFFFFU;
/// Owner of triangles whose corners lie in different strips.
inline constexpr std::uint8_t kSharedOwner = 0xFF;
/// Owner argument of an unrestricted insertion.
inline constexpr std::uint8_t kAnyOwner = 0xFE;
inline constexpr CavityTriangleId kNoCavityTriangle = 0xFFFFFFFFU;

/// Corners counter-clockwise; links[i] crosses the edge opposite corners[i].
struct CavityTriangle {
    std::array<CavityVertex, 3> corners;
    std::array<CavityLink, 3> links;
};

class CavityMesh {
public:
    /// A thread's working state: its region of fresh slots, the cavity and its boundary.
    /// Aligned to a cache line: the threads' scratches sit side by side in a vector.
    struct alignas(64) Scratch {
        CavityTriangleId regionBegin = 0;
        CavityTriangleId nextSlot = 0;
        CavityTriangleId regionEnd = 0;
        struct Frame {
            CavityTriangleId triangle;
            std::uint8_t nextEdge;
            std::uint8_t edgesLeft;
        };
        struct BoundaryEdge {
            CavityVertex from;
            CavityVertex to;
            CavityLink outside;
        };
        std::vector<Frame> stack;
        std::vector<CavityTriangleId> cavity;
        std::vector<BoundaryEdge> boundary;
    };

    /// `points`: distinct, they must outlive the insertions. `vertexStrip[v]`: the strip of vertex
    /// v (empty: one strip). `capacity`: slots of all regions together (address space only:
    /// pages are taken as slots are first used).
    CavityMesh(std::span<const Point2> points, std::span<const std::uint8_t> vertexStrip,
               std::size_t capacity);

    /// A scratch whose new triangles take the slots of a region of its own, `slots` long
    /// (an insertion needs two more slots than the triangles it replaces). Slots are
    /// numbered in the order of the regions' creation and, within a region, of use, so the
    /// extracted mesh does not depend on how threads interleave.
    [[nodiscard]] Scratch makeScratch(std::size_t slots);

    /// Makes the triangle a, b, c (not collinear) and its three ghosts, in slots of
    /// `scratch`; must come first. Returns the real triangle.
    CavityTriangleId start(CavityVertex a, CavityVertex b, CavityVertex c, Scratch& scratch);

    /// Inserts p, walking from `hint` (any triangle in use). With `owner` other than
    /// kAnyOwner, touches only triangles of that owner (the group `owner` of strips merged at
    /// `level`) and returns false, having changed nothing, when it would need another. On
    /// success `hint` becomes a triangle around p.
    bool insert(CavityVertex p, CavityTriangleId& hint, Scratch& scratch,
                std::uint8_t owner = kAnyOwner, unsigned level = 0);

    /// The triangle (real or ghost) in conflict with p found by walking from `start`, or
    /// kNoCavityTriangle when the walk would leave triangles of `owner` at `level`. Read-only.
    [[nodiscard]] CavityTriangleId locate(CavityVertex p, CavityTriangleId start,
                                          std::uint8_t owner = kAnyOwner, unsigned level = 0) const;

    /// Whether an insertion restricted to `owner` at `level` may touch triangle t.
    [[nodiscard]] bool mayTouch(CavityTriangleId t, std::uint8_t owner, unsigned level) const {
        if (owner == kAnyOwner)
            return true;
        const std::uint8_t label = m_owner[t];
        if (label != kSharedOwner)
            return (label >> level) == owner;
        return level != 0 && groupFromCorners(m_triangles[t].corners, level) == owner;
    }

    /// Records how far the scratch's region is used: extract() and memoryBytes() cover the
    /// slots of the regions as last recorded.
    void closeScratch(const Scratch& scratch);

    /// The real triangles in TinMesh form (corner order kept; neighbours across the edge from
    /// corner i to corner i + 1, kNoNeighbour on the hull), numbered in slot order. Reads the
    /// triangles alone: the points may be gone by then.
    void extract(MeshArray<std::uint32_t>& triangles, MeshArray<std::int32_t>& neighbours,
                 unsigned threads) const;

    /// Bytes of triangle slots and owners in use (as last recorded).
    [[nodiscard]] std::size_t memoryBytes() const;

private:
    [[nodiscard]] bool inConflict(const CavityTriangle& t, const Point2& p) const;
    [[nodiscard]] std::uint8_t ownerFromCorners(const std::array<CavityVertex, 3>& corners) const;
    /// The group at `level` holding all finite corners, or kSharedOwner.
    [[nodiscard]] std::uint8_t groupFromCorners(const std::array<CavityVertex, 3>& corners,
                                                unsigned level) const;
    CavityTriangleId allocate(Scratch& scratch);
    /// Collects into scratch the cavity of p, starting at triangle `first` (in conflict).
    /// Returns false when it meets a triangle in conflict that `owner` may not touch.
    bool collectCavity(const Point2& p, CavityTriangleId first, std::uint8_t owner, unsigned level,
                       Scratch& scratch) const;
    /// Replaces the cavity in scratch by the triangles joining p to its boundary.
    CavityTriangleId fillCavity(CavityVertex p, std::uint8_t owner, unsigned level,
                                Scratch& scratch);

    std::span<const Point2> m_points;
    std::span<const std::uint8_t> m_vertexStrip;
    HugePageBuffer<CavityTriangle> m_triangles;
    HugePageBuffer<std::uint8_t> m_owner;
    /// Per region, its first slot and the end of its used slots.
    std::vector<std::pair<CavityTriangleId, CavityTriangleId>> m_regions;
    std::size_t m_reserved = 0;
};

} // namespace terratin::detail

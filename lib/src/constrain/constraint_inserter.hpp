#pragma once
// The state of one insertConstraints call: the mutable mesh, the owners of constrained edges,
// and the pieces of segments still to insert.

#include "cdt_mesh.hpp"
#include "constraint_chains.hpp"
#include "constraint_owners.hpp"
#include "segment_cavity.hpp"
#include "segment_flips.hpp"
#include "terratin/constrain/constrained_tin.hpp"
#include "terratin/geometry/point.hpp"
#include "vertex_buckets.hpp"

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <set>
#include <vector>

namespace terratin::detail {

class ConstraintInserter {
public:
    /// `segments`: how many segments will be inserted (to size the tables).
    ConstraintInserter(TinMesh mesh, std::size_t segments) : m_mesh(std::move(mesh)) {
        m_owners.reserve(2 * segments);
    }

    /// The vertex at `p`'s x and y: an existing one, or a new one (sourceIndex
    /// kConstraintPointSource); nothing when `p` lies outside the convex hull. The search
    /// starts near the previous point, or anywhere when `jump` (the first point of a polyline).
    std::optional<std::uint32_t> insertPoint(const Point3& p, bool jump);
    /// insertPoint, the search starting from `triangle` (any triangle index of the mesh).
    std::optional<std::uint32_t> insertPointFrom(const Point3& p, std::size_t triangle);

    /// Makes the segment a -> b of input segment `owner` a chain of constrained edges,
    /// splitting it (and what it crosses) where needed.
    void insertSegment(std::uint32_t a, std::uint32_t b, std::uint32_t owner);

    /// The vertices of segment `owner`'s chain, from its first vertex to its last (final once
    /// every segment is inserted).
    [[nodiscard]] const std::vector<std::uint32_t>& chainOf(std::uint32_t owner) const {
        return m_chains.chain(owner);
    }

    /// Moves the mesh and the flags into `tin`, with the counts of added vertices.
    void finish(ConstrainedTin& tin);

private:
    struct Piece {
        std::uint32_t from;
        std::uint32_t to;
        ConstraintOwners::Owners owners;
    };

    void insertPiece(const Piece& piece);
    void markConstrained(std::size_t h, const ConstraintOwners::Owners& owners);
    void splitAtCrossing(std::uint32_t u, std::uint32_t v, const ConstraintOwners::Owners& owners,
                         std::size_t crossed);
    [[nodiscard]] std::optional<std::uint32_t> vertexWithinRounding(const Point3& p,
                                                                    std::size_t triangle) const;
    [[nodiscard]] std::optional<std::uint32_t> nearEndpoint(std::uint32_t u, std::uint32_t v,
                                                            std::uint32_t c, std::uint32_t d,
                                                            double sideC, double sideD) const;
    std::uint32_t insertVertex(const Point3& p, std::uint32_t source, const MeshLocation& where);

    CdtMesh m_mesh;
    ConstraintOwners m_owners;
    ConstraintChains m_chains;
    std::vector<Piece> m_pieces;
    /// The crossings (u, v, c, d) met while inserting the current segment: one met again means
    /// that rounding sends the pieces round in a circle (see splitAtCrossing).
    std::set<std::array<std::uint32_t, 4>> m_crossingsMet;
    CrossedEdges m_crossed;
    CavityScratch m_cavity;
    std::optional<VertexBuckets> m_buckets; // built for the first polyline
    std::size_t m_hintTriangle = 0;
    std::size_t m_addedPoints = 0;
    std::size_t m_intersections = 0;
};

} // namespace terratin::detail

#pragma once
/// @file
/// One tile's refined TIN and figures, and their bytes for another process (an MPI rank that
/// refined it, refine/tile_distribution.hpp).

#include "terratin/refine/refine.hpp"
#include "terratin/triangulate/tin_mesh.hpp"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace terratin::detail {

/// What one tile's refinement gives the whole (tile_refine.hpp).
/// A valid cell on a side of a tile, in the tile's own cell index, and its squared error there.
struct SideCell {
    std::uint32_t cell = 0;
    double squaredError = 0.0;
};

struct TileRefinement {
    /// sourceIndex = the tile's own cell index; no triangle when the tile's valid cells span
    /// no area.
    TinMesh mesh;
    /// Largest error over every valid cell of the tile, its sides' included.
    double maxError = 0.0;
    /// What stopped the tile's refiner: the error reached, or the tile's share of a point or
    /// triangle limit.
    RefineStop stop = RefineStop::ErrorReached;
    /// Over the cells the tile owns (its top and left sides, and its bottom and right ones only
    /// on the grid's edge, so that each cell of the grid has one owner): valid cells, open hole
    /// cells, valid cells inside a kept triangle, and the sum of their squared errors.
    std::size_t validCells = 0;
    std::size_t openHoleCells = 0;
    std::size_t coveredCells = 0;
    double sumSquares = 0.0;
    std::size_t droppedTriangles = 0;
    std::size_t hullPoints = 0;
    std::size_t strips = 0;
    std::size_t levels = 0;
    std::size_t deferredCandidates = 0;
    std::size_t pairInsertions = 0;
    std::size_t sharedInsertions = 0;
    std::size_t meshBytes = 0;
    /// A side's cell may be covered by one of its tiles only (the other's triangles there are
    /// over a hole). Each cell is counted by its owner (the tile below or to the right of a
    /// side: joined after the others), so: the cells of the tile's bottom and right sides that
    /// it covers, owned by the tiles after it (with their errors); and the cells of its top and
    /// left sides, shared with the tiles before it, that it leaves uncovered (tile_refine.cpp
    /// matches them).
    std::vector<SideCell> coveredForLaterTiles;
    std::vector<std::uint32_t> uncoveredSharedSides;
};

/// The bytes of `tile`, for unpackTile in a process of the same build.
std::vector<std::byte> packTile(const TileRefinement& tile);

/// The tile packTile packed. Throws Error when `bytes` are not whole (a truncated message).
TileRefinement unpackTile(const std::vector<std::byte>& bytes);

} // namespace terratin::detail

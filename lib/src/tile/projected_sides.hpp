#pragma once
/// @file
/// A tile side's vertices when the cells lie at projected positions (a geographic DEM refined
/// in its UTM zone, tile/projected_tile.hpp): chosen, like border_profile.hpp's, from that
/// side's cells alone, so that both tiles of the side keep the same ones. A projection bends a
/// row of cells, so the chords between kept cells must also stay clear of the cells beside the
/// side.

#include "terratin/geometry/point.hpp"

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

namespace terratin::detail {

/// One side of a tile as both tiles see it: a line of the raster's cells in increasing column
/// (or row) order, and the lines of cells on either side of it.
struct ProjectedSide {
    /// The side's elevations (NaN: no data) and positions.
    std::vector<float> z;
    std::vector<Point2> at;
    /// The lines beside it, cell for cell (empty where the raster ends): `before` at the row
    /// (column) before, `after` at the one after; elevations NaN where no data.
    std::vector<float> beforeZ;
    std::vector<Point2> before;
    std::vector<float> afterZ;
    std::vector<Point2> after;
    /// +1 when the `after` line lies to the left of the side followed in increasing order
    /// (exact orient2d > 0), -1 when to the right: the projection's orientation.
    int afterSign = 1;
};

/// The cells of `side` to keep as vertices, ascending: the two ends of every run of valid
/// cells, every valid cell next to or across from a cell without data on a line beside (the
/// tiles' triangles there may cover an open hole, and a cell on a chord is never inserted), and
/// the cells the Douglas-Peucker split needs for
/// - every valid cell of a run to lie within `tolerance` of the line between the kept cells on
///   either side of it, parametrised along their chord (where a cell lies on the chord, the TIN
///   interpolates exactly that);
/// - every valid cell beside a chord (of a run, or across a gap of no data between two runs)
///   to lie strictly on its own side of it, so that each tile's cells stay inside its own
///   boundary;
/// - where a line beside is missing (the raster's edge), no valid cell of the side to lie
///   strictly beyond its chord, so that the TIN covers it.
/// A chord over the tolerance splits at its worst cell, one that only bends too much at its
/// middle cell. Without a tolerance, every valid cell is kept (full resolution). Throws
/// InvalidInputError when a chord across a gap of no data bends past a valid cell beside it (no
/// cell of the gap can split it: the tiles must be smaller), Error when two neighbouring cells'
/// chord does.
std::vector<std::uint32_t> keptProjectedSideCells(const ProjectedSide& side,
                                                  std::optional<double> tolerance);

} // namespace terratin::detail

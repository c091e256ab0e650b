#pragma once
// Other libraries' Delaunay triangulators, timed on the same points as terratin's: CGAL
// (optional at build time) and GDAL (always built).

#include "terratin/geometry/point.hpp"

#include <cstddef>
#include <memory>
#include <span>
#include <string>
#include <string_view>

namespace terratin::bench {

/// A triangulator from another library.
///
/// The bench calls prepare() once per point set (untimed: it converts the points into the
/// peer's own input), then for each run triangulate() (the timed call, which keeps its
/// triangulation alive so that freeing it is not timed) and release().
class Peer {
public:
    virtual ~Peer() = default;

    /// The column and row label: "cgal" or "gdal".
    [[nodiscard]] virtual std::string_view name() const = 0;

    /// Library, version and call, for the table's preamble.
    [[nodiscard]] virtual std::string description() const = 0;

    /// Copies x and y of `points` into the peer's input format.
    virtual void prepare(std::span<const Point3> points) = 0;

    /// Triangulates the prepared points; returns the number of finite triangles.
    /// Throws terratin::Error when the peer fails.
    virtual std::size_t triangulate() = 0;

    /// Frees the last triangulation.
    virtual void release() = 0;
};

/// Whether terratin-bench was built with CGAL (TERRATIN_HAVE_CGAL).
bool cgalBuilt();

/// CGAL's Delaunay_triangulation_2 with the Exact_predicates_inexact_constructions_kernel,
/// filled with its range insert (which sorts the points along a Hilbert curve first).
/// Throws terratin::Error when terratin-bench was built without CGAL (see cgalBuilt()).
std::unique_ptr<Peer> makeCgalPeer();

/// Whether terratin-bench was built with GDAL (TERRATIN_HAVE_GDAL: with terratin::io).
bool gdalBuilt();

/// Whether the GDAL linked in can triangulate (it needs qhull); false when none is.
bool gdalHasTriangulation();

/// GDAL's GDALTriangulationCreateDelaunay (qhull underneath).
/// Throws terratin::Error when GDAL was built without triangulation support, or not built in.
std::unique_ptr<Peer> makeGdalPeer();

} // namespace terratin::bench

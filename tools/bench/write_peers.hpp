#pragma once
// The peers of terratin-bench --write: what a user would otherwise run to turn a DEM into
// GeoPackage triangles, and the least SQLite itself needs to store the same rows and index.

#include "terratin/geometry/point.hpp"
#include "terratin/triangulate/tin_mesh.hpp"

#include <array>
#include <cstddef>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

namespace terratin::bench {

/// Whether the GDAL + CGAL + OGR script can run (terratin-bench built with CGAL).
bool scriptPeerBuilt();

/// The 70-line script a user would write instead of terratin: GDAL reads the band's valid cell
/// centres, CGAL's Delaunay_triangulation_2 triangulates them, OGR writes one Polygon Z per
/// triangle with one z_mean field, in one transaction, with GDAL's default spatial index. Returns
/// the triangles written. Throws terratin::Error on failure or when built without CGAL.
std::size_t runGdalCgalOgrScript(const std::string& dem, const std::filesystem::path& output);

/// A plain OGR loop over `triangles`: one CreateFeature per triangle with terratin's 14
/// attributes, in one transaction, GDAL's default spatial index. Throws terratin::Error.
void writeWithOgrLoop(const std::vector<std::array<Point3, 3>>& triangles,
                      const std::string& crsWkt, const std::filesystem::path& output);

/// The triangles of a GeoPackage layer, read back with OGR (to hand a plain loop the same
/// triangles terratin wrote). Throws terratin::Error.
std::vector<std::array<Point3, 3>> readTriangles(const std::filesystem::path& gpkg,
                                                 std::string* crsWkt);

/// The bound on a GeoPackage write through SQLite: a minimal program that stores rows of the
/// same shape (fid, a 165-byte blob, 14 doubles) in a table keyed INTEGER PRIMARY KEY
/// AUTOINCREMENT, with one prepared many-row statement in one transaction, journal off, and
/// a packed R-tree written into the R*Tree's shadow tables. prepare() builds every byte
/// beforehand (untimed); write() is the timed SQLite work alone.
class SqliteLimitPeer {
public:
    SqliteLimitPeer();
    ~SqliteLimitPeer();
    void prepare(const TinMesh& mesh);
    void write(const std::filesystem::path& output) const;

private:
    struct Prepared;
    std::unique_ptr<Prepared> m_prepared;
};

} // namespace terratin::bench

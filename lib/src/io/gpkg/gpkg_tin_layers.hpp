#pragma once
/// @file
/// The rows and the index boxes of terratin's three GeoPackage layers, written straight into
/// the tables OGR created: triangles (Polygon Z with attribute columns), nodes (Point Z) and
/// edges (LineString Z). Feature ids are 1-based in mesh order, so that the edge layer's
/// tri_left / tri_right and the node ids refer to them; a TIN written piece by piece
/// (tin_stream.hpp) continues the numbers of the pieces before.

#include "gpkg_feature_table.hpp"
#include "packed_rtree.hpp"
#include "sqlite_connection.hpp"

#include "terratin/io/tin_writer.hpp"
#include "terratin/triangulate/tin_mesh.hpp"

#include <cstdint>
#include <functional>
#include <span>
#include <string_view>
#include <vector>

namespace terratin::io::detail {

/// progress(rows done in this layer): called before each chunk; may throw to cancel.
using RowProgress = std::function<void(std::uint64_t)>;

/// Inserts one row per triangle: fid (firstFid for the mesh's first triangle, then one after
/// another), geometry and the columns of `attributes`.
void insertTriangleRows(SqliteConnection& connection, const GpkgFeatureTable& table,
                        const TinMesh& mesh, AttributeSet attributes, std::int64_t firstFid,
                        const RowProgress& progress);

/// Inserts one row per vertex: fid (from firstFid on), geometry, id = fid, and row / col when
/// `cells` is not empty.
void insertNodeRows(SqliteConnection& connection, const GpkgFeatureTable& table,
                    const TinMesh& mesh, std::span<const RasterCell> cells, std::int64_t firstFid,
                    const RowProgress& progress);

/// Inserts one row per edge: fid, geometry, node_from, node_to, tri_left, tri_right (NULL on
/// the hull), length (3D) and constrained (constrainedEdges[3t+i], 0 when empty). Edges come
/// in mesh order, see forEachEdge.
void insertEdgeRows(SqliteConnection& connection, const GpkgFeatureTable& table,
                    const TinMesh& mesh, std::span<const std::uint8_t> constrainedEdges,
                    const RowProgress& progress);

/// The number of edges: interior edges are shared by two triangles, hull edges belong to one.
std::uint64_t edgeCount(const TinMesh& mesh);

/// Index boxes of the features of each layer, box i for fid i + 1.
std::vector<RtreeBox> triangleBoxes(const TinMesh& mesh);
std::vector<RtreeBox> nodeBoxes(const TinMesh& mesh);
std::vector<RtreeBox> edgeBoxes(const TinMesh& mesh);

/// The x/y extent of the mesh's vertices: that of every layer.
Extent2d meshExtent(const TinMesh& mesh);

} // namespace terratin::io::detail

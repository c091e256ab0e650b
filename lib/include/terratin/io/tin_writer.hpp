#pragma once
/// @file
/// writeTin: the one entry point that writes a TinMesh in any output format.

#include "terratin/io/tin_format.hpp"
#include "terratin/progress.hpp"
#include "terratin/triangulate/tin_mesh.hpp"
#include "terratin/version.hpp"

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace terratin::io {

/// Which triangle attributes the vector formats carry.
enum class AttributeSet {
    /// Geometry only.
    None,
    /// z_min z_max z_mean slope_deg aspect_deg area_2d.
    Basic,
    /// z1 z2 z3 z_min z_max z_mean slope_deg slope_pct aspect_deg area_2d area_3d nx ny nz.
    All,
};

/// The raster cell a vertex came from (for the GeoPackage nodes layer), 0-based.
struct RasterCell {
    std::int64_t row = 0;
    std::int64_t col = 0;
};

/// How to write.
struct TinWriteOptions {
    TinFormat format = TinFormat::GeoPackage;
    /// Replace an existing output (with appendLayer: replace existing layers of the same names).
    bool overwrite = false;
    /// CRS of the vertices as WKT; empty writes no CRS.
    std::string crsWkt;
    /// Name of the triangle layer (GeoPackage; FlatGeobuf and Shapefile name the layer after
    /// the file). The node and edge layers are "nodes" and "edges" when it is "tin", else
    /// "<layerName>_nodes" and "<layerName>_edges". Well-formed UTF-8 without control
    /// characters (U+0000 to U+001F, U+007F) or U+FFFE / U+FFFF (which XML cannot hold):
    /// checkTinWriteOptions refuses anything else.
    std::string layerName = "tin";
    /// Attribute columns of the triangles (vector formats; the mesh formats carry none).
    AttributeSet attributes = AttributeSet::All;
    /// GeoPackage only: a Point Z layer of the vertices (fid and id = vertex number from 1,
    /// and row / col when vertexCells is given).
    bool nodes = false;
    /// GeoPackage only: a LineString Z layer of the edges (node_from, node_to, tri_left,
    /// tri_right = triangle fids, tri_right NULL on the hull, length = 3D length in CRS units,
    /// constrained = 1 on a breakline, else 0).
    bool edges = false;
    /// GeoPackage only: add the layers to an existing GeoPackage, leaving its other layers as
    /// they are (a new file is created when it does not exist). The file is changed in place
    /// in one SQLite transaction, under SQLite's locks and its own journal or WAL, so that
    /// another program's reads and writes of it are never lost.
    bool appendLayer = false;
    /// With appendLayer: how long to wait, in seconds in all, for another program's lock on
    /// the GeoPackage (a writer's open transaction) before giving up with an error. Progress
    /// is reported while waiting, so a cancellation ends the wait at once.
    double lockWaitSeconds = 30.0;
    /// GeoPackage only: build the R-tree spatial index (one pass after the inserts). Without it
    /// the file is valid and QGIS reads it, but spatial filters scan every row.
    bool spatialIndex = true;
    /// Vector formats: also write "<output without extension>.qml", a QGIS style that colours
    /// the triangles by z_mean on a terrain ramp (needs attributes basic or all).
    bool qgisStyle = false;
    /// For a DEM input: vertexCells[v] is the raster cell of vertex v (size = vertex count);
    /// empty otherwise.
    std::vector<RasterCell> vertexCells;
    /// A constrained TIN: constrainedEdges[3t+i] is 1 when the edge from corner i of triangle t
    /// to corner (i+1)%3 lies on a breakline (size = 3 x triangle count); empty: none is.
    MeshArray<std::uint8_t> constrainedEdges;
    /// LandXML: the breaklines, each as the TIN vertices it runs through, written as
    /// <Breakline> elements of the surface's <SourceData>.
    std::vector<std::vector<Point3>> breaklines;
    /// Software version written into LandXML's Application element (and the PLY / OBJ
    /// headers): this library's by default.
    std::string softwareVersion = kVersionString;
};

/// What was written.
struct TinWriteResult {
    /// Features (vector formats: triangles + nodes + edges) or elements (mesh formats:
    /// vertices + faces) written.
    std::uint64_t features = 0;
    /// GeoPackage: seconds spent inserting the rows of every layer, and building their
    /// spatial indexes (0 for the other formats).
    double rowSeconds = 0.0;
    double indexSeconds = 0.0;
};

/// Throws InvalidInputError when the options contradict each other or the format (nodes,
/// edges, appendLayer or spatialIndex=false outside GeoPackage; qgisStyle with a mesh format
/// or without attributes; a layer name holding a control character, such as a newline, which
/// would corrupt the text formats, or bytes that are not UTF-8; vertexCells of the wrong size
/// is checked by writeTin). The
/// message marks the options it names (markOption): "nodes needs a GeoPackage output".
void checkTinWriteOptions(const TinWriteOptions& options);

/// Refuses, before anything is read or computed, the output writeTin would refuse: a location
/// that cannot take it (IoError), an existing file of the output without options.overwrite
/// (InvalidInputError; for a Shapefile any component or sidecar of the same base name, .prj
/// .cpg .qix .qml ... in either case), and one that is not a regular file, whatever
/// options.overwrite says (IoError: a device, a FIFO, a symbolic link). writeTin checks again,
/// and its final rename checks atomically once more.
void checkTinOutput(const std::filesystem::path& output, const TinWriteOptions& options);

/// Writes the mesh in options.format.
/// Vector formats: one Polygon Z feature per triangle (closed counter-clockwise ring, vertex
/// z = elevation; a Shapefile stores it clockwise, as its specification demands) with the
/// attributes of options.attributes, plus the optional node / edge layers and QGIS style.
/// Mesh formats: see two_dm_writer, ply_writer, obj_writer, landxml_writer (vertex numbers
/// are from 1 in 2DM, OBJ and LandXML, from 0 in PLY; faces counter-clockwise).
/// Atomicity: every file is written under a temporary name in the output's directory and
/// renamed into place only when complete; on any failure (or Cancelled) the temporaries are
/// removed and an existing output is left untouched (with appendLayer the existing GeoPackage
/// is extended in place in one SQLite transaction, which a failure rolls back; a GeoPackage
/// that is read-only, fails SQLite's quick_check or is not a GeoPackage is refused before
/// anything is written). Without `overwrite` the
/// final rename refuses atomically an output that another program created during the run.
/// Throws IoError, InvalidInputError (existing output without `overwrite`, empty mesh, a
/// Shapefile past its 2 GB limits, contradictory options), CrsError (unusable `crsWkt`),
/// Cancelled. A GeoPackage without CRS is labelled "Undefined Cartesian SRS".
TinWriteResult writeTin(const TinMesh& mesh, const std::filesystem::path& output,
                        const TinWriteOptions& options, const ProgressCallback& progress = {});

/// Name of the node / edge layer that goes with the triangle layer `layerName`.
std::string nodeLayerName(const std::string& layerName);
std::string edgeLayerName(const std::string& layerName);

} // namespace terratin::io

#pragma once
/// @file
/// A Shapefile's or a FlatGeobuf's triangle layer: its creation with the attribute fields, and
/// the triangles inserted as Polygon Z features. Shared by the writer of a whole TIN
/// (ogr_tin_writer.cpp) and the one that takes it tile by tile (ogr_tin_stream.cpp).

#include "terratin/io/tin_writer.hpp"
#include "writer_support.hpp"

#include <gdal_priv.h>
#include <ogr_spatialref.h>
#include <ogrsf_frmts.h>

#include <cstddef>
#include <filesystem>
#include <limits>
#include <optional>
#include <string>

namespace terratin::io::detail {

struct TriangleLayerSpec {
    /// The layer's name: the output's stem (a Shapefile's and a FlatGeobuf's layer is named
    /// after its file).
    std::string name;
    /// Shapefile or FlatGeobuf.
    TinFormat format = TinFormat::Shapefile;
    /// FlatGeobuf with a spatial index: TEMPORARY_DIR, empty for GDAL's default (the output's
    /// directory).
    std::string temporaryDirectory = {};
};

/// The Polygon Z layer of `spec` in `dataset`, with a field per attribute of
/// options.attributes. A Shapefile's is created without the DBF end-of-file mark, which
/// appendLastTriangle writes. Throws IoError naming `output`.
OGRLayer& createTriangleLayer(GDALDataset& dataset, const TriangleLayerSpec& spec,
                              std::optional<OGRSpatialReference>& srs,
                              const TinWriteOptions& options, const std::filesystem::path& output);

/// Triangles [first, last) of a mesh, `last` clamped to its triangle count.
struct TriangleRange {
    std::size_t first = 0;
    std::size_t last = std::numeric_limits<std::size_t>::max();
};

/// Inserts one feature per triangle of `range` into a layer of createTriangleLayer, with its
/// attributes (computed a chunk ahead of the inserts). Throws IoError, Cancelled (by
/// `ticker`), InvalidInputError (an attribute too large for a DBF column).
void writeTriangles(OGRLayer& layer, const TinMesh& mesh, const TinWriteOptions& options,
                    const ProgressTicker& ticker, const std::filesystem::path& output,
                    TriangleRange range = {});

/// Appends the last triangle of `mesh` to the closed Shapefile `shp`, in an update session
/// whose DBF writes the end-of-file mark after the record, as a single session would have.
void appendLastTriangle(const TinMesh& mesh, const std::filesystem::path& shp,
                        const TinWriteOptions& options, const ProgressTicker& ticker,
                        const std::filesystem::path& output);

/// Refuses (InvalidInputError naming GeoPackage as the way out) a Shapefile whose .shp or
/// .dbf would pass the format's 2 GB limit. The sizes are exact: every record has the same
/// size (one 4-point PolygonZ ring; fixed-width numeric columns).
void checkShapefileLimits(std::size_t triangleCount, AttributeSet attributes,
                          const std::filesystem::path& output);

} // namespace terratin::io::detail

#pragma once
// What GDAL/OGR alone needs to write a TIN: plain OGR loops, nothing of terratin's writer, so
// that a benchmark can put terratin's Shapefile and FlatGeobuf writers next to the bound the
// driver sets.

#include "terratin/triangulate/tin_mesh.hpp"

#include <filesystem>
#include <string>

namespace terratin::bench {

/// The layout and options of a minimal write. The defaults are those of terratin's writer
/// (lib/src/io/ogr_tin_writer.cpp); change one to measure what it costs.
struct MinimalWriteOptions {
    /// Attribute columns: the 14 of AttributeSet::All, all OFTReal.
    bool attributes = true;
    /// Shapefile: width and precision of each DBF "N" column.
    int dbfWidth = 24;
    int dbfPrecision = 12;
    /// Shapefile: the layer creation option DBF_EOF_CHAR (the 0x1A after the last record).
    /// terratin writes its records without it and appends the last one in a second session
    /// that writes the mark; one record more or less is noise here.
    bool dbfEofChar = false;
    /// FlatGeobuf: the packed Hilbert R-tree GDAL builds at close.
    bool spatialIndex = true;
    /// FlatGeobuf: the layer creation option TEMPORARY_DIR (where GDAL keeps the features
    /// until it sorts them at close); empty leaves GDAL's default, the output's directory.
    std::string temporaryDir = "/vsimem/";
};

/// Seconds GDAL's Shapefile driver takes to create `dir`/minimal.shp (.shx, .dbf) holding one
/// PolygonZ per triangle of `mesh`, with one reused OGRFeature and its attributes computed
/// before the clock starts; the time ends when the dataset is closed. The files are removed
/// afterwards. `dir` must exist. Throws terratin::IoError when GDAL fails.
double timeMinimalShapefileWrite(const TinMesh& mesh, const std::filesystem::path& dir,
                                 const MinimalWriteOptions& options = {});

/// The same for `dir`/minimal.fgb through GDAL's FlatGeobuf driver.
double timeMinimalFlatGeobufWrite(const TinMesh& mesh, const std::filesystem::path& dir,
                                  const MinimalWriteOptions& options = {});

} // namespace terratin::bench

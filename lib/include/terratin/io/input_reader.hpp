#pragma once
/// @file
/// InputReader: one entry point for every input terratin builds from. It decides what a file
/// is (raster, LAS, delimited text, OGR vector) and hands it to the reader for that kind.

#include "terratin/io/las_reader.hpp"
#include "terratin/io/ogr_point_reader.hpp"
#include "terratin/io/point_source.hpp"
#include "terratin/io/raster_reader.hpp"
#include "terratin/io/text_reader.hpp"
#include "terratin/progress.hpp"

#include <string>

namespace terratin::io {

/// Options of every reader; each input uses those of its kind.
struct InputReadOptions {
    RasterReadOptions raster;
    LasReadOptions las;
    TextReadOptions text;
    OgrPointReadOptions vector;
};

/// What `path` is, decided in this order:
/// 1. LAS: the file starts with "LASF", or its extension is .las / .laz;
/// 2. text: extension .xyz .txt .pts .tsv .dat, or .csv unless its first line names a
///    WKT / geometry column (then it is OGR's CSV with geometry);
/// 3. raster or vector: whatever GDAL opens (raster bands win over vector layers);
/// 4. text again for any other file without NUL bytes in its first 64 KiB.
/// Throws IoError when the file does not exist or none of these applies.
InputKind detectInputKind(const std::string& path);

/// Reads `path` with the reader of detectInputKind(path). Rasters carry cellIndex and
/// skippedCells, recordsRead = width * height. A text file takes its CRS from a sidecar
/// .prj beside it (same name), when there is one.
/// Throws what the chosen reader throws (see each reader's header).
PointCloud readInput(const std::string& path, const InputReadOptions& options = {},
                     const ProgressCallback& progress = {});

} // namespace terratin::io

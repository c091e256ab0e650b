#pragma once
/// @file
/// AsciiPgmReader: plain (ASCII, "P2") PGM heightfields, which GDAL's PNM driver does not read
/// (it reads the binary P5 and P6 only). Netpbm's format: "P2", width, height, maxval, then
/// width * height decimal samples in 0..maxval, row by row from the top, separated by
/// whitespace; '#' starts a comment that runs to the end of the line.

#include <gdal.h>

#include <string>
#include <string_view>

namespace terratin::io::detail {

/// Whether `start`, the first bytes of a file, is the signature of a plain PGM: "P2" and then
/// whitespace.
bool isAsciiPgm(std::string_view start);

/// Reads the plain PGM at `path` into a one-band GDAL MEM dataset (UInt16) without
/// georeferencing, as GDAL presents a binary PGM: no geotransform (cell (row, col) centred at
/// (col + 0.5, row + 0.5)), no CRS, no nodata. The caller owns the handle (GDALClose).
/// Throws IoError when the file cannot be read, InvalidInputError naming `stage` when it is not
/// a well-formed plain PGM (bad header, sample above maxval, fewer samples than the header
/// declares).
/// O(file size) time; 2 bytes per cell, plus GDAL's copy of the same size.
GDALDatasetH openAsciiPgm(const std::string& path, std::string_view stage);

} // namespace terratin::io::detail

/// @file
/// InputReader: dispatch by content first (the LAS signature), then by extension for text, then
/// by what GDAL recognises.

#include "terratin/io/input_reader.hpp"

#include "ascii_pgm.hpp"

#include "../text.hpp"
#include "terratin/crs/reprojection.hpp"
#include "terratin/error.hpp"
#include "terratin/gdal_error.hpp"

#include <gdal.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>
#include <optional>

namespace terratin::io {

using terratin::detail::lowercase;

namespace {

constexpr std::string_view kStage = "InputReader";
/// Bytes looked at to call an unrecognised file text.
constexpr std::size_t kSniffBytes = 65536;

namespace fs = std::filesystem;

std::string lowercaseExtension(const std::string& path) {
    return lowercase(fs::path(path).extension().string());
}

std::string head(const std::string& path, std::size_t bytes) {
    std::ifstream file(path, std::ios::binary);
    std::string data(bytes, '\0');
    file.read(data.data(), static_cast<std::streamsize>(bytes));
    data.resize(static_cast<std::size_t>(std::max<std::streamsize>(file.gcount(), 0)));
    return data;
}

/// Whether a CSV's header line names a geometry column that OGR's CSV driver reads.
bool csvHasGeometryColumn(const std::string& path) {
    std::string line = head(path, 4096);
    line = line.substr(0, line.find('\n'));
    if (line.rfind("\xEF\xBB\xBF", 0) == 0) // a UTF-8 byte order mark
        line.erase(0, 3);
    line = lowercase(line);
    for (char& c : line)
        if (c == '"' || c == '\r' || c == ' ' || c == ';' || c == '\t')
            c = ',';
    line = "," + line + ",";
    for (const char* name : {",wkt,", ",geometry,", ",geom,", ",the_geom,"})
        if (line.find(name) != std::string::npos)
            return true;
    return false;
}

struct DatasetCloser {
    void operator()(void* dataset) const { GDALClose(dataset); }
};

} // namespace

const char* toString(InputKind kind) {
    switch (kind) {
    case InputKind::Raster:
        return "raster";
    case InputKind::Las:
        return "las";
    case InputKind::Laz:
        return "laz";
    case InputKind::Text:
        return "text";
    case InputKind::Vector:
        return "vector";
    }
    return "unknown";
}

/// Whether `path` may be a GDAL connection string or subdataset name ("GPKG:file.gpkg:table",
/// "NETCDF:\"file.nc\":var", "PG:dbname=...") rather than a file: a prefix of two or more
/// letters, digits or underscores, then a colon. "C:" (a drive letter) is not one.
bool looksLikeConnectionString(const std::string& path) {
    const std::size_t colon = path.find(':');
    if (colon == std::string::npos || colon < 2)
        return false;
    return std::all_of(path.begin(), path.begin() + static_cast<std::ptrdiff_t>(colon),
                       [](unsigned char c) { return std::isalnum(c) != 0 || c == '_'; });
}

namespace {

/// The kind a file's first bytes or its extension tell (LAS, text, a CSV with or without a
/// geometry column, an ASCII PGM); nullopt to ask GDAL.
std::optional<InputKind> kindOfFile(const std::string& path) {
    const std::string start = head(path, 4);
    const std::string ext = lowercaseExtension(path);
    if (start == "LASF" || ext == ".las" || ext == ".laz")
        return InputKind::Las;
    if (ext == ".xyz" || ext == ".txt" || ext == ".pts" || ext == ".tsv" || ext == ".dat")
        return InputKind::Text;
    if (ext == ".csv")
        return csvHasGeometryColumn(path) ? InputKind::Vector : InputKind::Text;
    // An ASCII PGM, which GDAL's PNM driver does not read; the raster reader does.
    if (detail::isAsciiPgm(start))
        return InputKind::Raster;
    return std::nullopt;
}

/// The kind GDAL opens `path` as; nullopt when it opens it as nothing.
std::optional<InputKind> kindByGdal(const std::string& path) {
    initialiseGdal();
    CPLErrorReset();
    const std::unique_ptr<void, DatasetCloser> dataset(GDALOpenEx(
        path.c_str(), GDAL_OF_RASTER | GDAL_OF_VECTOR | GDAL_OF_READONLY | GDAL_OF_VERBOSE_ERROR,
        nullptr, nullptr, nullptr));
    if (!dataset)
        return std::nullopt;
    if (GDALGetRasterCount(dataset.get()) > 0)
        return InputKind::Raster;
    if (GDALDatasetGetLayerCount(dataset.get()) > 0)
        return InputKind::Vector;
    // A container of subdatasets: the raster reader explains how to pick one.
    return InputKind::Raster;
}

/// Whether a file no reader recognised is to be read as text: unless it starts like JSON or
/// XML (a damaged GeoJSON or GML should get GDAL's message, not a line-number complaint).
bool readsAsText(const std::string& path) {
    const std::string sample = head(path, kSniffBytes);
    const std::size_t first = sample.find_first_not_of(" \t\r\n");
    return first != std::string::npos && sample[first] != '{' && sample[first] != '<' &&
           sample.find('\0') == std::string::npos;
}

} // namespace

InputKind detectInputKind(const std::string& path) {
    const bool virtualPath = path.rfind("/vsi", 0) == 0;
    std::error_code error;
    const fs::file_status status = virtualPath ? fs::file_status() : fs::status(path, error);
    // Not a file: GDAL may still open it as a connection string or subdataset name.
    const bool gdalName = !virtualPath && !fs::exists(status) && looksLikeConnectionString(path);
    if (!virtualPath && !gdalName) {
        if (!fs::exists(status)) {
            // ENOENT, or the reason it cannot be looked at: a symbolic link loop, a component
            // that is not a directory, permission denied.
            const std::string reason = error && error != std::errc::no_such_file_or_directory
                                           ? error.message()
                                           : std::string("no such file or directory");
            throw IoError(std::string(kStage) + ": cannot open '" + path + "': " + reason);
        }
        // A directory can be a vector dataset (a folder of Shapefiles); GDAL decides below.
        if (!fs::is_directory(status))
            if (const std::optional<InputKind> kind = kindOfFile(path))
                return *kind;
    }
    if (const std::optional<InputKind> kind = kindByGdal(path))
        return *kind;
    if (gdalName)
        throw IoError(std::string(kStage) + ": cannot open '" + path +
                      "': no such file, and GDAL does not open it as a dataset name: " +
                      lastGdalErrorMessage());
    if (!virtualPath && !fs::is_directory(status) && readsAsText(path))
        return InputKind::Text;
    throw IoError(std::string(kStage) + ": '" + path +
                  "' is not a raster, LAS, text or vector file terratin can read: " +
                  lastGdalErrorMessage("GDAL recognises no format in it"));
}

PointCloud readInput(const std::string& path, const InputReadOptions& options,
                     const ProgressCallback& progress) {
    switch (detectInputKind(path)) {
    case InputKind::Raster: {
        RasterPoints raster = readRasterPoints(path, options.raster, progress);
        PointCloud cloud;
        cloud.path = path;
        cloud.kind = InputKind::Raster;
        cloud.points = std::move(raster.points);
        cloud.cellIndex = std::move(raster.cellIndex);
        cloud.rasterWidth = static_cast<std::uint64_t>(raster.width);
        cloud.rasterHeight = static_cast<std::uint64_t>(raster.height);
        cloud.rasterGeoTransform = raster.geoTransform.c;
        cloud.crsWkt = std::move(raster.crsWkt);
        cloud.recordsRead =
            static_cast<std::uint64_t>(raster.width) * static_cast<std::uint64_t>(raster.height);
        cloud.skippedCells = raster.skippedCells;
        return cloud;
    }
    case InputKind::Las:
    case InputKind::Laz: // detected as LAS; the LAS reader decodes LAZ
        return readLasPoints(path, options.las, progress);
    case InputKind::Text: {
        PointCloud cloud = readTextPoints(path, options.text, progress);
        fs::path prj = fs::path(path).replace_extension(".prj");
        std::error_code error;
        if (!fs::exists(prj, error))
            prj = fs::path(path).replace_extension(".PRJ");
        if (fs::exists(prj, error))
            cloud.crsWkt = crs::crsFromUserInput(prj.string(), "the sidecar file");
        return cloud;
    }
    case InputKind::Vector:
        return readOgrPoints(path, options.vector, progress);
    }
    throw InvalidInputError(std::string(kStage) + ": unknown kind of input '" + path + "'");
}

} // namespace terratin::io

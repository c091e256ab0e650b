#pragma once
/// @file
/// The OGR dataset steps every vector writer shares: the output CRS, creating a dataset under
/// its temporary name, and closing it with its errors reported.

#include <gdal_priv.h>
#include <ogr_spatialref.h>

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

namespace terratin::io::detail {

/// The stage every OGR writer's messages start with.
inline constexpr std::string_view kOgrStage = "OgrTinWriter";

/// The CRS of `wkt` with x = easting, y = northing (nullopt for an empty string). Throws
/// CrsError when it is not valid WKT.
std::optional<OGRSpatialReference> parseOutputCrs(const std::string& wkt);

/// A new dataset of `driverName` at `path` (the temporary name of `output`). Throws IoError.
GDALDatasetUniquePtr createDataset(const char* driverName, const std::filesystem::path& path,
                                   const std::filesystem::path& output);

/// Closes the dataset and turns a failure while flushing (disk full...) into IoError.
void closeDataset(GDALDatasetUniquePtr& dataset, const std::filesystem::path& output);

} // namespace terratin::io::detail

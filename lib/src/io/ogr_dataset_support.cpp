#include "ogr_dataset_support.hpp"

#include "atomic_output.hpp"
#include "terratin/error.hpp"
#include "terratin/gdal_error.hpp"

#include <cpl_error.h>

namespace terratin::io::detail {

std::optional<OGRSpatialReference> parseOutputCrs(const std::string& wkt) {
    if (wkt.empty())
        return std::nullopt;
    std::optional<OGRSpatialReference> srs(std::in_place);
    if (srs->importFromWkt(wkt.c_str()) != OGRERR_NONE)
        throw CrsError(std::string(kOgrStage) +
                       ": the output CRS is not valid WKT: " + lastGdalErrorMessage());
    // x = easting, y = northing whatever the CRS's declared axis order: that is how the mesh
    // stores its coordinates.
    srs->SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
    return srs;
}

GDALDatasetUniquePtr createDataset(const char* driverName, const std::filesystem::path& path,
                                   const std::filesystem::path& output) {
    GDALDriver* driver = GetGDALDriverManager()->GetDriverByName(driverName);
    if (driver == nullptr)
        throw IoError(std::string(kOgrStage) + ": GDAL has no '" + driverName +
                      "' driver, needed for " + quoted(output));
    CPLErrorReset();
    GDALDatasetUniquePtr dataset(driver->Create(path.c_str(), 0, 0, 0, GDT_Unknown, nullptr));
    if (!dataset)
        throwGdalError(kOgrStage, "cannot create a temporary file for", output.string());
    return dataset;
}

void closeDataset(GDALDatasetUniquePtr& dataset, const std::filesystem::path& output) {
    // GDAL 3.6's GDALClose reports nothing, so the error state is the only witness.
    CPLErrorReset();
    dataset.reset();
    if (CPLGetLastErrorType() == CE_Failure || CPLGetLastErrorType() == CE_Fatal)
        throwGdalError(kOgrStage, "cannot finish writing", output.string());
}

} // namespace terratin::io::detail

/// @file
/// OgrPointReader: point features through the OGR C++ API, one feature at a time.

#include "terratin/io/ogr_point_reader.hpp"

#include "../crs/wkt.hpp"
#include "terratin/error.hpp"
#include "terratin/gdal_error.hpp"

#include <gdal_priv.h>
#include <ogrsf_frmts.h>

#include <charconv>
#include <cmath>
#include <memory>
#include <optional>

namespace terratin::io {

namespace {

constexpr std::string_view kStage = "OgrPointReader";
/// Features between two progress reports.
constexpr std::uint64_t kProgressEvery = 65536;

bool isPointType(OGRwkbGeometryType type) {
    const OGRwkbGeometryType flat = wkbFlatten(type);
    return flat == wkbPoint || flat == wkbMultiPoint;
}

std::string layerNames(GDALDataset& dataset) {
    std::string names;
    for (OGRLayer* layer : dataset.GetLayers()) {
        if (!names.empty())
            names += ", ";
        names += std::string("'") + layer->GetName() + "' (" +
                 OGRGeometryTypeToName(layer->GetGeomType()) + ")";
    }
    return names.empty() ? std::string("none") : names;
}

OGRLayer* chooseLayer(GDALDataset& dataset, const std::string& path, const std::string& wanted) {
    if (!wanted.empty()) {
        OGRLayer* layer = dataset.GetLayerByName(wanted.c_str());
        if (layer == nullptr)
            throw InvalidInputError(std::string(kStage) + ": '" + path + "' has no layer '" +
                                    wanted + "'; its layers: " + layerNames(dataset));
        return layer;
    }
    // A declared point layer first; then a layer of unknown (mixed) geometry type, whose
    // point features are read and the rest counted as filtered out.
    for (OGRLayer* layer : dataset.GetLayers())
        if (isPointType(layer->GetGeomType()))
            return layer;
    for (OGRLayer* layer : dataset.GetLayers())
        if (wkbFlatten(layer->GetGeomType()) == wkbUnknown ||
            wkbFlatten(layer->GetGeomType()) == wkbGeometryCollection)
            return layer;
    throw InvalidInputError(std::string(kStage) + ": '" + path +
                            "' has no point layer; its layers: " + layerNames(dataset));
}

std::string layerCrs(OGRLayer& layer, const std::string& path) {
    const OGRSpatialReference* srs = layer.GetSpatialRef();
    if (srs == nullptr)
        return {};
    std::string wkt = crs::detail::exportWkt(*srs);
    if (wkt.empty())
        throw CrsError(
            std::string(kStage) + ": '" + path + "': the CRS of layer '" + layer.GetName() +
            "' cannot be exported: " + lastGdalErrorMessage("PROJ has no WKT1 or WKT2 form of it"));
    return wkt;
}

} // namespace

PointCloud readOgrPoints(const std::string& path, const OgrPointReadOptions& options,
                         const ProgressCallback& progress) {
    initialiseGdal();
    CPLErrorReset();
    const std::unique_ptr<GDALDataset> dataset(
        GDALDataset::Open(path.c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY | GDAL_OF_VERBOSE_ERROR));
    if (!dataset)
        throwGdalError(kStage, "cannot open vector data", path,
                       "GDAL recognises no vector data in it");
    OGRLayer* layer = chooseLayer(*dataset, path, options.layer);
    const std::string where =
        std::string(kStage) + ": '" + path + "' layer '" + layer->GetName() + "': ";

    int zFieldIndex = -1;
    OGRFieldType zFieldType = OFTReal;
    if (!options.zField.empty()) {
        OGRFeatureDefn* definition = layer->GetLayerDefn();
        zFieldIndex = definition->GetFieldIndex(options.zField.c_str());
        if (zFieldIndex < 0) {
            std::string fields;
            for (int i = 0; i < definition->GetFieldCount(); ++i)
                fields += std::string(i ? ", " : "") + definition->GetFieldDefn(i)->GetNameRef();
            throw InvalidInputError(where + "no field '" + options.zField + "' (fields: " +
                                    (fields.empty() ? std::string("none") : fields) + ")");
        }
        zFieldType = definition->GetFieldDefn(zFieldIndex)->GetType();
        if (zFieldType != OFTInteger && zFieldType != OFTInteger64 && zFieldType != OFTReal &&
            zFieldType != OFTString)
            throw InvalidInputError(where + "field '" + options.zField + "' is " +
                                    OGRFieldDefn::GetFieldTypeName(zFieldType) + ", not a number");
    }

    PointCloud cloud;
    cloud.path = path;
    cloud.kind = InputKind::Vector;
    cloud.crsWkt = layerCrs(*layer, path);
    const GIntBig featureCount = layer->GetFeatureCount(FALSE);
    if (featureCount > 0)
        cloud.points.reserve(static_cast<std::size_t>(featureCount));

    // The elevation a feature gives its points: the z field, or nothing (use the geometry's).
    const auto fieldZ = [&](const OGRFeature& feature, double& z) {
        if (!feature.IsFieldSetAndNotNull(zFieldIndex))
            return false;
        if (zFieldType != OFTString) {
            z = feature.GetFieldAsDouble(zFieldIndex);
        } else {
            const std::string_view text = feature.GetFieldAsString(zFieldIndex);
            const auto [ptr, error] = std::from_chars(text.data(), text.data() + text.size(), z);
            if (error != std::errc() || ptr != text.data() + text.size())
                throw InvalidInputError(where + "feature " + std::to_string(feature.GetFID()) +
                                        ": field '" + options.zField + "' ('" + std::string(text) +
                                        "') is not a number");
        }
        if (!std::isfinite(z))
            throw InvalidInputError(where + "feature " + std::to_string(feature.GetFID()) +
                                    ": field '" + options.zField + "' is not finite");
        return true;
    };
    const auto addPoint = [&](const OGRPoint& point, std::optional<double> z) {
        if (point.IsEmpty())
            return false;
        if (!z) {
            if (!point.Is3D())
                throw InvalidInputError(where +
                                        "its points have no z; name the elevation attribute "
                                        "with " +
                                        markOption("z_field"));
            z = point.getZ();
        }
        cloud.points.push_back({point.getX(), point.getY(), *z});
        return true;
    };

    layer->ResetReading();
    for (auto& feature : *layer) {
        ++cloud.recordsRead;
        std::optional<double> z;
        if (zFieldIndex >= 0) {
            double value = 0.0;
            if (!fieldZ(*feature, value)) {
                ++cloud.filteredOut;
                continue;
            }
            z = value;
        }
        const OGRGeometry* geometry = feature->GetGeometryRef();
        bool added = false;
        if (geometry != nullptr) {
            const OGRwkbGeometryType type = wkbFlatten(geometry->getGeometryType());
            if (type == wkbPoint) {
                added = addPoint(*geometry->toPoint(), z);
            } else if (type == wkbMultiPoint) {
                for (const OGRPoint* point : *geometry->toMultiPoint())
                    added = addPoint(*point, z) || added;
            }
        }
        if (!added)
            ++cloud.filteredOut;
        if (progress && featureCount > 0 && cloud.recordsRead % kProgressEvery == 0 &&
            !progress(std::min(1.0, static_cast<double>(cloud.recordsRead) /
                                        static_cast<double>(featureCount)),
                      "reading points"))
            throw Cancelled(std::string(kStage) + ": cancelled while reading '" + path + "'");
    }
    if (cloud.points.empty())
        throw InvalidInputError(where + "no point among its " + std::to_string(cloud.recordsRead) +
                                " feature(s)");
    return cloud;
}

} // namespace terratin::io

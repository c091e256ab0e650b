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
#include <string>
#include <utility>

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

/// The attribute that gives the points their elevation (OgrPointReadOptions::zField), or
/// none: the geometry's z.
struct ZField {
    int index = -1;
    OGRFieldType type = OFTReal;
};

/// The z field `options` names, checked in `layer`'s definition; `where` starts messages.
ZField zFieldOf(OGRLayer& layer, const OgrPointReadOptions& options, const std::string& where) {
    ZField z;
    if (options.zField.empty())
        return z;
    OGRFeatureDefn* definition = layer.GetLayerDefn();
    z.index = definition->GetFieldIndex(options.zField.c_str());
    if (z.index < 0) {
        std::string fields;
        for (int i = 0; i < definition->GetFieldCount(); ++i)
            fields += std::string(i ? ", " : "") + definition->GetFieldDefn(i)->GetNameRef();
        throw InvalidInputError(where + "no field '" + options.zField + "' (fields: " +
                                (fields.empty() ? std::string("none") : fields) + ")");
    }
    z.type = definition->GetFieldDefn(z.index)->GetType();
    if (z.type != OFTInteger && z.type != OFTInteger64 && z.type != OFTReal && z.type != OFTString)
        throw InvalidInputError(where + "field '" + options.zField + "' is " +
                                OGRFieldDefn::GetFieldTypeName(z.type) + ", not a number");
    return z;
}

/// The points of one layer's features, added to a cloud one feature at a time.
class FeaturePoints {
public:
    FeaturePoints(const ZField& zField, const OgrPointReadOptions& options, std::string where,
                  PointCloud& cloud)
        : m_zField(zField), m_options(options), m_where(std::move(where)), m_cloud(cloud) {}

    /// Adds the feature's points (a point, or each of a multipoint's); counts it as filtered
    /// out when it gives none (no geometry, another type, empty points, a null z field).
    void add(const OGRFeature& feature) {
        ++m_cloud.recordsRead;
        std::optional<double> z;
        if (m_zField.index >= 0) {
            double value = 0.0;
            if (!fieldZ(feature, value)) {
                ++m_cloud.filteredOut;
                return;
            }
            z = value;
        }
        const OGRGeometry* geometry = feature.GetGeometryRef();
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
            ++m_cloud.filteredOut;
    }

private:
    /// The elevation the feature's z field gives; false when it is not set.
    bool fieldZ(const OGRFeature& feature, double& z) const {
        if (!feature.IsFieldSetAndNotNull(m_zField.index))
            return false;
        if (m_zField.type != OFTString) {
            z = feature.GetFieldAsDouble(m_zField.index);
        } else {
            const std::string_view text = feature.GetFieldAsString(m_zField.index);
            const auto [ptr, error] = std::from_chars(text.data(), text.data() + text.size(), z);
            if (error != std::errc() || ptr != text.data() + text.size())
                throw InvalidInputError(m_where + "feature " + std::to_string(feature.GetFID()) +
                                        ": field '" + m_options.zField + "' ('" +
                                        std::string(text) + "') is not a number");
        }
        if (!std::isfinite(z))
            throw InvalidInputError(m_where + "feature " + std::to_string(feature.GetFID()) +
                                    ": field '" + m_options.zField + "' is not finite");
        return true;
    }

    bool addPoint(const OGRPoint& point, std::optional<double> z) {
        if (point.IsEmpty())
            return false;
        if (!z) {
            if (!point.Is3D())
                throw InvalidInputError(m_where +
                                        "its points have no z; name the elevation attribute "
                                        "with " +
                                        markOption("z_field"));
            z = point.getZ();
        }
        m_cloud.points.push_back({point.getX(), point.getY(), *z});
        return true;
    }

    ZField m_zField;
    const OgrPointReadOptions& m_options;
    std::string m_where;
    PointCloud& m_cloud;
};

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
    const ZField zField = zFieldOf(*layer, options, where);

    PointCloud cloud;
    cloud.path = path;
    cloud.kind = InputKind::Vector;
    cloud.crsWkt = layerCrs(*layer, path);
    const GIntBig featureCount = layer->GetFeatureCount(FALSE);
    if (featureCount > 0)
        cloud.points.reserve(static_cast<std::size_t>(featureCount));

    FeaturePoints points(zField, options, where, cloud);
    layer->ResetReading();
    for (auto& feature : *layer) {
        points.add(*feature);
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

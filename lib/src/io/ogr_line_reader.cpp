/// @file
/// OgrLineReader: line features through the OGR C++ API, one feature at a time.

#include "terratin/io/ogr_line_reader.hpp"

#include "../crs/wkt.hpp"
#include "terratin/error.hpp"
#include "terratin/gdal_error.hpp"

#include <gdal_priv.h>
#include <ogrsf_frmts.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <memory>

namespace terratin::io {

namespace {

constexpr std::string_view kStage = "OgrLineReader";
constexpr std::string_view kLayerSuffix = "|layername=";

struct SourceName {
    std::string path;
    std::string layer;
};

SourceName splitSource(const std::string& source) {
    const std::size_t bar = source.rfind(kLayerSuffix);
    if (bar == std::string::npos)
        return {source, {}};
    return {source.substr(0, bar), source.substr(bar + kLayerSuffix.size())};
}

std::string layerList(GDALDataset& dataset) {
    std::string names;
    for (OGRLayer* layer : dataset.GetLayers())
        names += (names.empty() ? "'" : ", '") + std::string(layer->GetName()) + "'";
    return names.empty() ? std::string("none") : names;
}

OGRLayer* chooseLayer(GDALDataset& dataset, const std::string& where, const std::string& wanted) {
    if (!wanted.empty()) {
        OGRLayer* layer = dataset.GetLayerByName(wanted.c_str());
        if (layer == nullptr)
            throw InvalidInputError(where + "no layer '" + wanted +
                                    "'; its layers: " + layerList(dataset));
        return layer;
    }
    if (dataset.GetLayerCount() != 1)
        throw InvalidInputError(where + "holds " + std::to_string(dataset.GetLayerCount()) +
                                " layers (" + layerList(dataset) +
                                "): name one with FILE|layername=NAME");
    return dataset.GetLayer(0);
}

/// Whether `srs` is what GDAL's GeoPackage driver reports for the specification's srs_id 0
/// ("Undefined geographic SRS") or -1 ("Undefined Cartesian SRS"): a layer stored without a
/// CRS, not one in degrees of an unknown datum.
bool isUndefinedGeoPackageCrs(const OGRSpatialReference& srs) {
    const char* name = srs.GetName();
    return name != nullptr && (std::strcmp(name, "Undefined geographic SRS") == 0 ||
                               std::strcmp(name, "Undefined Cartesian SRS") == 0);
}

std::string layerCrs(OGRLayer& layer, const std::string& where) {
    const OGRSpatialReference* srs = layer.GetSpatialRef();
    if (srs == nullptr || isUndefinedGeoPackageCrs(*srs))
        return {};
    std::string wkt = crs::detail::exportWkt(*srs);
    if (wkt.empty())
        throw CrsError(where + "its CRS cannot be exported: " +
                       lastGdalErrorMessage("PROJ has no WKT1 or WKT2 form of it"));
    return wkt;
}

/// Adds one LineString's points; false when it is empty.
bool addLine(const OGRLineString& line, std::int64_t fid, const std::string& where,
             LineLayer& layer) {
    if (line.IsEmpty())
        return false;
    const bool hasZ = line.Is3D();
    layer.hasZ = layer.hasZ || hasZ;
    std::vector<Point3> points;
    points.reserve(static_cast<std::size_t>(line.getNumPoints()));
    for (int i = 0; i < line.getNumPoints(); ++i) {
        const Point3 point{line.getX(i), line.getY(i),
                           hasZ ? line.getZ(i) : std::numeric_limits<double>::quiet_NaN()};
        if (!std::isfinite(point.x) || !std::isfinite(point.y) || (hasZ && !std::isfinite(point.z)))
            throw InvalidInputError(where + "feature " + std::to_string(fid) + ": point " +
                                    std::to_string(i + 1) + " is not finite");
        points.push_back(point);
    }
    layer.lines.push_back(std::move(points));
    layer.featureIds.push_back(fid);
    return true;
}

void addGeometry(const OGRGeometry& geometry, std::int64_t fid, const std::string& where,
                 LineLayer& layer) {
    const OGRwkbGeometryType type = wkbFlatten(geometry.getGeometryType());
    if (type == wkbLineString) {
        addLine(*geometry.toLineString(), fid, where, layer);
        return;
    }
    if (type == wkbMultiLineString) {
        for (const OGRLineString* part : *geometry.toMultiLineString())
            addLine(*part, fid, where, layer);
        return;
    }
    throw InvalidInputError(where + "feature " + std::to_string(fid) + " is a " +
                            OGRGeometryTypeToName(geometry.getGeometryType()) +
                            ", not a LineString or MultiLineString");
}

void addPolygon(const OGRPolygon& polygon, std::int64_t fid, const std::string& where,
                LineLayer& layer) {
    const std::size_t number = layer.polygonOf.empty() ? 0 : layer.polygonOf.back() + 1;
    for (const OGRLinearRing* ring : polygon)
        if (addLine(*ring, fid, where, layer))
            layer.polygonOf.push_back(number);
}

void addPolygons(const OGRGeometry& geometry, std::int64_t fid, const std::string& where,
                 LineLayer& layer) {
    const OGRwkbGeometryType type = wkbFlatten(geometry.getGeometryType());
    if (type != wkbPolygon && type != wkbMultiPolygon)
        throw InvalidInputError(where + "feature " + std::to_string(fid) + " is a " +
                                OGRGeometryTypeToName(geometry.getGeometryType()) +
                                ", not a Polygon or MultiPolygon");
    // The rings first: they refuse a vertex that is not finite, which GEOS would call a
    // crossing. The layer is dropped whole when a feature is refused.
    if (type == wkbPolygon) {
        addPolygon(*geometry.toPolygon(), fid, where, layer);
    } else {
        for (const OGRPolygon* part : *geometry.toMultiPolygon())
            addPolygon(*part, fid, where, layer);
    }
    if (!geometry.IsValid())
        throw InvalidInputError(where + "feature " + std::to_string(fid) +
                                " is not a valid polygon (a ring crosses itself or another)");
}

std::string fieldList(const OGRFeatureDefn& definition) {
    std::string names;
    for (int i = 0; i < definition.GetFieldCount(); ++i)
        names += (names.empty() ? "'" : ", '") +
                 std::string(definition.GetFieldDefn(i)->GetNameRef()) + "'";
    return names.empty() ? std::string("none") : names;
}

/// The index of the numeric field `name` in `layer`.
int numericField(OGRLayer& layer, const std::string& name, const std::string& where) {
    const OGRFeatureDefn& definition = *layer.GetLayerDefn();
    const int index = definition.GetFieldIndex(name.c_str());
    if (index < 0)
        throw InvalidInputError(where + "no field '" + name +
                                "'; its fields: " + fieldList(definition));
    const OGRFieldType type = definition.GetFieldDefn(index)->GetType();
    if (type != OFTInteger && type != OFTInteger64 && type != OFTReal)
        throw InvalidInputError(where + "field '" + name + "' is not numeric (" +
                                OGRFieldDefn::GetFieldTypeName(type) + ")");
    return index;
}

/// Feature `feature`'s value of field `index`, finite.
double featureValue(const OGRFeature& feature, int index, const std::string& where) {
    const double value = feature.GetFieldAsDouble(index);
    if (!feature.IsFieldSetAndNotNull(index) || !std::isfinite(value))
        throw InvalidInputError(where + "feature " + std::to_string(feature.GetFID()) +
                                " has no value in field '" +
                                feature.GetFieldDefnRef(index)->GetNameRef() + "'");
    return value;
}

using AddFeature = void (*)(const OGRGeometry&, std::int64_t, const std::string&, LineLayer&);

LineLayer readLayer(const std::string& source, const std::string& layerName,
                    const std::string& option, AddFeature add, const std::string& valueField = {}) {
    initialiseGdal();
    CPLErrorReset();
    const SourceName name = splitSource(source);
    const std::unique_ptr<GDALDataset> dataset(GDALDataset::Open(
        name.path.c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY | GDAL_OF_VERBOSE_ERROR));
    if (!dataset)
        throwGdalError(kStage, "cannot open the vector data of " + option, name.path,
                       "GDAL recognises no vector data in it");
    const std::string fileWhere = std::string(kStage) + ": " + option + " '" + name.path + "' ";
    OGRLayer* layer = chooseLayer(*dataset, fileWhere, layerName.empty() ? name.layer : layerName);
    const std::string where = std::string(kStage) + ": " + option + " '" + name.path + "' layer '" +
                              layer->GetName() + "': ";

    LineLayer lines;
    lines.source = source;
    lines.layerName = layer->GetName();
    lines.crsWkt = layerCrs(*layer, where);
    const int valueIndex = valueField.empty() ? -1 : numericField(*layer, valueField, where);
    layer->ResetReading();
    for (const auto& feature : *layer) {
        const OGRGeometry* geometry = feature->GetGeometryRef();
        if (geometry == nullptr || geometry->IsEmpty())
            continue;
        add(*geometry, feature->GetFID(), where, lines);
        if (valueIndex >= 0) {
            const std::size_t polygons = lines.polygonOf.empty() ? 0 : lines.polygonOf.back() + 1;
            lines.polygonValues.resize(polygons, featureValue(*feature, valueIndex, where));
        }
    }
    return lines;
}

} // namespace

LineLayer readOgrLines(const std::string& source, const std::string& layer,
                       const std::string& option) {
    return readLayer(source, layer, option, addGeometry);
}

LineLayer readOgrPolygons(const std::string& source, const std::string& layer,
                          const std::string& option, const std::string& valueField) {
    return readLayer(source, layer, option, addPolygons, valueField);
}

} // namespace terratin::io

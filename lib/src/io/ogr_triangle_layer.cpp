/// @file
/// The triangle layer of a Shapefile or a FlatGeobuf (see ogr_tin_writer.cpp for why the
/// features are written the way they are).

#include "ogr_triangle_layer.hpp"

#include "atomic_output.hpp"
#include "attribute_columns.hpp"
#include "chunk_pipeline.hpp"
#include "ogr_dataset_support.hpp"
#include "terratin/error.hpp"
#include "terratin/gdal_error.hpp"

#include <cpl_conv.h>
#include <cpl_error.h>
#include <ogr_feature.h>
#include <ogr_geometry.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <span>
#include <string_view>
#include <utility>
#include <vector>

namespace terratin::io::detail {

namespace fs = std::filesystem;

namespace {

constexpr std::string_view kStage = kOgrStage;

/// The ESRI Shapefile specification limits .shp and .dbf to 2 GB (offsets in 16-bit words
/// stored in signed 32-bit integers). GDAL can go to 4 GB, but other readers cannot.
constexpr std::uint64_t kShapefileMaxBytes = 2'147'483'647;

/// .shp: the 100-byte file header, then per PolygonZ record with one 4-point ring and no M:
/// 8 record header + 4 type + 32 box + 4 numParts + 4 numPoints + 4 part index
/// + 4 * 16 xy + 16 z range + 4 * 8 z = 168 bytes.
constexpr std::uint64_t kShpHeaderBytes = 100;
constexpr std::uint64_t kShpRecordBytes = 168;

/// DBF column layout of every attribute: a fixed-point "N" column. 12 decimals resolve far
/// below any DEM's precision (1e-12 m, 1e-12 degree).
constexpr int kDbfRealWidth = 24;
constexpr int kDbfRealPrecision = 12;
/// A value printed "%24.12f" that comes out longer than 24 characters is cut to its first 24
/// by shapelib (GDAL only warns, and CreateFeature succeeds). With k integer digits and a
/// sign, 22 - k decimals survive, more than the 17 - k a double holds, so the value reads back
/// the same, as long as the integer part itself fits: beyond that the value silently loses
/// whole orders of magnitude (1e25 reads back as 1e23). Checked with GDAL 3.6.2. Values at or
/// beyond this bound (k >= 23) are refused.
constexpr double kDbfMaxMagnitude = 1e22;
/// A DBF without any attribute column still needs one: GDAL adds a 10-character "FID" column.
constexpr int kDbfDefaultColumnWidth = 10;

[[noreturn]] void throwIo(const std::string& message) {
    throw IoError(std::string(kStage) + ": " + message);
}

[[noreturn]] void throwInvalid(const std::string& message) {
    throw InvalidInputError(std::string(kStage) + ": " + message);
}

OGRLayer* createLayer(GDALDataset& dataset, const TriangleLayerSpec& spec,
                      std::optional<OGRSpatialReference>& srs, const TinWriteOptions& options,
                      const fs::path& output) {
    CPLStringList layerOptions;
    switch (spec.format) {
    case TinFormat::Shapefile:
        layerOptions.SetNameValue("SHPT", "POLYGONZ");
        layerOptions.SetNameValue("ENCODING", "UTF-8");
        // Backstop for the up-front size check: GDAL would otherwise grow files to 4 GB.
        layerOptions.SetNameValue("2GB_LIMIT", "YES");
        // appendLastTriangle writes the end-of-file mark (ogr_tin_writer.cpp says why).
        layerOptions.SetNameValue("DBF_EOF_CHAR", "NO");
        break;
    case TinFormat::FlatGeobuf:
        layerOptions.SetNameValue("SPATIAL_INDEX", options.spatialIndex ? "YES" : "NO");
        if (!spec.temporaryDirectory.empty())
            layerOptions.SetNameValue("TEMPORARY_DIR", spec.temporaryDirectory.c_str());
        break;
    default:
        throwInvalid("not an OGR format");
    }
    CPLErrorReset();
    OGRLayer* layer = dataset.CreateLayer(spec.name.c_str(), srs ? &*srs : nullptr, wkbPolygon25D,
                                          layerOptions.List());
    if (layer == nullptr)
        throwGdalError(kStage, "cannot create the layer '" + spec.name + "' of", output.string());
    return layer;
}

void addField(OGRLayer& layer, const char* name, OGRFieldType type, TinFormat format,
              const fs::path& output) {
    OGRFieldDefn definition(name, type);
    if (format == TinFormat::Shapefile && type == OFTReal) {
        definition.SetWidth(kDbfRealWidth);
        definition.SetPrecision(kDbfRealPrecision);
    }
    if (layer.CreateField(&definition) != OGRERR_NONE)
        throwGdalError(kStage, std::string("cannot create the field ") + name + " of",
                       output.string());
}

int fieldIndex(OGRLayer& layer, const char* name, const fs::path& output) {
    const int index = layer.GetLayerDefn()->GetFieldIndex(name);
    if (index < 0)
        throwIo(std::string("the driver did not keep the field ") + name + " in " + quoted(output));
    return index;
}

void createFeature(OGRLayer& layer, OGRFeature& feature, std::string_view what, std::uint64_t id,
                   const fs::path& output) {
    if (layer.CreateFeature(&feature) != OGRERR_NONE)
        throwGdalError(kStage,
                       "cannot write " + std::string(what) + " " + std::to_string(id) + " to",
                       output.string());
}

/// The one feature and the one polygon that carry every triangle of a layer in turn: the
/// ring's 4 points and the attribute fields are overwritten in place, so no geometry is
/// allocated per triangle.
class TriangleFeature {
public:
    /// `checkDbf`: refuse a value that does not fit a Shapefile's DBF column.
    TriangleFeature(OGRLayer& layer, std::span<const AttributeColumn> columns,
                    const fs::path& output, bool checkDbf)
        : m_layer(layer), m_columns(columns), m_output(output), m_checkDbf(checkDbf),
          m_feature(OGRFeature::CreateFeature(layer.GetLayerDefn())) {
        for (const AttributeColumn& column : columns)
            m_indices.push_back(fieldIndex(layer, column.name, output));
        m_ring = new OGRLinearRing();
        for (int i = 0; i < 4; ++i)
            m_ring->setPoint(i, 0.0, 0.0, 0.0);
        auto* polygon = new OGRPolygon();
        polygon->addRingDirectly(m_ring);
        polygon->set3D(TRUE);
        m_feature->SetGeometryDirectly(polygon);
        for (const int index : m_indices)
            m_feature->SetField(index, 0.0);
    }

    /// The closed ring a, b, c, a.
    void setCorners(const Point3& a, const Point3& b, const Point3& c) {
        m_ring->setPoint(0, a.x, a.y, a.z);
        m_ring->setPoint(1, b.x, b.y, b.z);
        m_ring->setPoint(2, c.x, c.y, c.z);
        m_ring->setPoint(3, a.x, a.y, a.z);
    }

    /// The attribute fields of triangle `t`.
    void setAttributes(const TriangleAttributes& values, std::size_t t) {
        for (std::size_t i = 0; i < m_columns.size(); ++i) {
            const double value = values.*(m_columns[i].member);
            if (m_checkDbf && !(std::fabs(value) < kDbfMaxMagnitude))
                throwInvalid("triangle " + std::to_string(t) + " has " + m_columns[i].name + " = " +
                             std::to_string(value) +
                             ", which does not fit a Shapefile's DBF column; write a "
                             "GeoPackage (.gpkg) instead of " +
                             quoted(m_output));
            // The raw field: SetField's type dispatch and set-marker bookkeeping cost more
            // than the insert of a FlatGeobuf feature itself. Every field was set (to 0) at
            // the start, and a finite double never matches OGR's unset / null markers (NaN
            // bit patterns).
            m_feature->GetRawFieldRef(m_indices[i])->Real = value;
        }
    }

    /// Inserts the feature as triangle `t`.
    void write(std::size_t t) {
        // The driver numbers; a reused feature must be reset, or the next insert would
        // collide with the FID CreateFeature stored in it.
        m_feature->SetFID(OGRNullFID);
        createFeature(m_layer, *m_feature, "triangle", t, m_output);
    }

private:
    OGRLayer& m_layer;
    std::span<const AttributeColumn> m_columns;
    const fs::path& m_output;
    bool m_checkDbf;
    std::vector<int> m_indices;
    OGRFeatureUniquePtr m_feature;
    OGRLinearRing* m_ring = nullptr; // owned by the feature's polygon
};

/// Triangles per attribute chunk: the progress interval, so each chunk ends with a report.
constexpr std::size_t kChunkTriangles = kProgressInterval;

} // namespace

OGRLayer& createTriangleLayer(GDALDataset& dataset, const TriangleLayerSpec& spec,
                              std::optional<OGRSpatialReference>& srs,
                              const TinWriteOptions& options, const fs::path& output) {
    OGRLayer* layer = createLayer(dataset, spec, srs, options, output);
    for (const auto& column : attributeColumns(options.attributes))
        addField(*layer, column.name, OFTReal, spec.format, output);
    return *layer;
}

void writeTriangles(OGRLayer& layer, const TinMesh& mesh, const TinWriteOptions& options,
                    const ProgressTicker& ticker, const fs::path& output, TriangleRange range) {
    const std::span<const AttributeColumn> columns = attributeColumns(options.attributes);
    TriangleFeature feature(layer, columns, output, options.format == TinFormat::Shapefile);
    const std::size_t first = range.first;
    const std::size_t last = std::min(mesh.triangleCount(), range.last);
    const std::size_t chunks =
        last > first ? (last - first + kChunkTriangles - 1) / kChunkTriangles : 0;
    const auto chunkRange = [&](std::size_t chunk) {
        const std::size_t begin = first + chunk * kChunkTriangles;
        return std::pair{begin, std::min(last, begin + kChunkTriangles)};
    };
    // The attributes of a chunk are computed beside the writer, which writes the one before.
    const auto prepare = [&](std::size_t chunk, std::vector<TriangleAttributes>& attributes) {
        if (!columns.empty()) {
            const auto [begin, end] = chunkRange(chunk);
            computeAttributes(mesh, begin, end, attributes);
        }
    };
    const auto consume = [&](std::size_t chunk, const std::vector<TriangleAttributes>& attributes) {
        const auto [begin, end] = chunkRange(chunk);
        ticker.report(begin, "Writing triangles");
        for (std::size_t t = begin; t < end; ++t) {
            feature.setCorners(mesh.vertices[mesh.triangles[3 * t]],
                               mesh.vertices[mesh.triangles[3 * t + 1]],
                               mesh.vertices[mesh.triangles[3 * t + 2]]);
            if (!columns.empty())
                feature.setAttributes(attributes[t - begin], t);
            feature.write(t);
        }
    };
    runBesideOneWriter<std::vector<TriangleAttributes>>(chunks, prepare, consume);
}

void appendLastTriangle(const TinMesh& mesh, const fs::path& shp, const TinWriteOptions& options,
                        const ProgressTicker& ticker, const fs::path& output) {
    const char* const drivers[] = {"ESRI Shapefile", nullptr};
    const char* const openOptions[] = {"DBF_EOF_CHAR=YES", nullptr};
    CPLErrorReset();
    GDALDatasetUniquePtr dataset(GDALDataset::Open(shp.c_str(), GDAL_OF_VECTOR | GDAL_OF_UPDATE,
                                                   drivers, openOptions, nullptr));
    OGRLayer* layer = dataset ? dataset->GetLayer(0) : nullptr;
    if (layer == nullptr)
        throwGdalError(kStage, "cannot reopen the Shapefile being written for", output.string());
    writeTriangles(*layer, mesh, options, ticker, output,
                   {mesh.triangleCount() - 1, mesh.triangleCount()});
    closeDataset(dataset, output);
}

void checkShapefileLimits(std::size_t triangleCount, AttributeSet attributes,
                          const fs::path& output) {
    const auto count = static_cast<std::uint64_t>(triangleCount);
    const std::uint64_t shpBytes = kShpHeaderBytes + count * kShpRecordBytes;
    // .dbf: 32-byte header, 32 bytes per field descriptor, a terminator, one deletion flag
    // plus the fixed-width columns per record, and an end-of-file marker.
    const std::uint64_t columns = attributeColumns(attributes).size();
    const std::uint64_t recordBytes = columns == 0
                                          ? std::uint64_t{kDbfDefaultColumnWidth}
                                          : columns * static_cast<std::uint64_t>(kDbfRealWidth);
    const std::uint64_t dbfBytes =
        32 + 32 * std::max<std::uint64_t>(columns, 1) + 1 + count * (1 + recordBytes) + 1;
    const std::uint64_t largest = std::max(shpBytes, dbfBytes);
    if (largest > kShapefileMaxBytes)
        throwInvalid(std::to_string(triangleCount) + " triangles need about " +
                     std::to_string(largest / (1024 * 1024)) +
                     " MiB per Shapefile component, over the format's 2 GB limit; write a "
                     "GeoPackage (.gpkg) instead of " +
                     quoted(output));
}

} // namespace terratin::io::detail

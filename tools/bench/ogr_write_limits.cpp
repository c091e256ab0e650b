#include "ogr_write_limits.hpp"

#include "attribute_columns.hpp"

#include "terratin/error.hpp"
#include "terratin/geometry/triangle_attributes.hpp"

#include <cpl_error.h>
#include <cpl_string.h>
#include <gdal_priv.h>
#include <ogr_feature.h>
#include <ogr_geometry.h>
#include <ogrsf_frmts.h>

#include <array>
#include <chrono>
#include <string>
#include <system_error>
#include <vector>

namespace terratin::bench {

namespace {

namespace fs = std::filesystem;

/// The columns of AttributeSet::All, in terratin's output order.
const auto kColumns = io::detail::attributeColumns(io::AttributeSet::All);

[[noreturn]] void fail(const std::string& what, const fs::path& path) {
    throw IoError("ogr_write_limits: " + what + " " + path.string() + ": " + CPLGetLastErrorMsg());
}

std::vector<TriangleAttributes> allAttributes(const TinMesh& mesh) {
    std::vector<TriangleAttributes> attributes(mesh.triangleCount());
    for (std::size_t t = 0; t < attributes.size(); ++t)
        attributes[t] = computeTriangleAttributes(mesh.vertices[mesh.triangles[3 * t]],
                                                  mesh.vertices[mesh.triangles[3 * t + 1]],
                                                  mesh.vertices[mesh.triangles[3 * t + 2]]);
    return attributes;
}

/// Creates `path` with `driverName`, one PolygonZ layer and the columns, inserts every
/// triangle and closes the dataset; returns the seconds from Create to the end of the close.
double timeWrite(const TinMesh& mesh, const char* driverName, const fs::path& path,
                 CPLStringList& layerOptions, int realWidth, int realPrecision,
                 const MinimalWriteOptions& options) {
    GDALAllRegister();
    GDALDriver* driver = GetGDALDriverManager()->GetDriverByName(driverName);
    if (driver == nullptr)
        fail(std::string("no GDAL driver ") + driverName + " for", path);
    const std::vector<TriangleAttributes> attributes =
        options.attributes ? allAttributes(mesh) : std::vector<TriangleAttributes>{};

    const auto start = std::chrono::steady_clock::now();
    {
        GDALDatasetUniquePtr dataset(driver->Create(path.c_str(), 0, 0, 0, GDT_Unknown, nullptr));
        if (!dataset)
            fail("cannot create", path);
        OGRLayer* layer =
            dataset->CreateLayer(path.stem().c_str(), nullptr, wkbPolygon25D, layerOptions.List());
        if (layer == nullptr)
            fail("cannot create the layer of", path);
        if (options.attributes) {
            for (const auto& column : kColumns) {
                OGRFieldDefn definition(column.name, OFTReal);
                definition.SetWidth(realWidth);
                definition.SetPrecision(realPrecision);
                if (layer->CreateField(&definition) != OGRERR_NONE)
                    fail("cannot create a field of", path);
            }
        }
        OGRFeatureUniquePtr feature(OGRFeature::CreateFeature(layer->GetLayerDefn()));
        auto* ring = new OGRLinearRing();
        for (int i = 0; i < 4; ++i)
            ring->setPoint(i, 0.0, 0.0, 0.0);
        auto* polygon = new OGRPolygon();
        polygon->addRingDirectly(ring);
        feature->SetGeometryDirectly(polygon);
        if (options.attributes)
            for (int i = 0; i < static_cast<int>(kColumns.size()); ++i)
                feature->SetField(i, 0.0);
        for (std::size_t t = 0; t < mesh.triangleCount(); ++t) {
            const Point3& a = mesh.vertices[mesh.triangles[3 * t]];
            const Point3& b = mesh.vertices[mesh.triangles[3 * t + 1]];
            const Point3& c = mesh.vertices[mesh.triangles[3 * t + 2]];
            ring->setPoint(0, a.x, a.y, a.z);
            ring->setPoint(1, b.x, b.y, b.z);
            ring->setPoint(2, c.x, c.y, c.z);
            ring->setPoint(3, a.x, a.y, a.z);
            // The raw field, as terratin's writer does: every field was set once before the
            // loop, and a finite double never matches OGR's unset / null markers.
            if (options.attributes)
                for (int i = 0; i < static_cast<int>(kColumns.size()); ++i)
                    feature->GetRawFieldRef(i)->Real = attributes[t].*(kColumns[i].member);
            feature->SetFID(OGRNullFID);
            if (layer->CreateFeature(feature.get()) != OGRERR_NONE)
                fail("cannot write a feature to", path);
        }
        CPLErrorReset();
        dataset.reset();
        if (CPLGetLastErrorType() == CE_Failure)
            fail("cannot finish", path);
    }
    const std::chrono::duration<double> seconds = std::chrono::steady_clock::now() - start;
    return seconds.count();
}

void removeAll(const std::vector<fs::path>& paths) {
    for (const fs::path& path : paths) {
        std::error_code ignored;
        fs::remove(path, ignored);
    }
}

} // namespace

double timeMinimalShapefileWrite(const TinMesh& mesh, const fs::path& dir,
                                 const MinimalWriteOptions& options) {
    const fs::path shp = dir / "minimal.shp";
    const std::vector<fs::path> files = {shp, dir / "minimal.shx", dir / "minimal.dbf",
                                         dir / "minimal.cpg"};
    removeAll(files);
    CPLStringList layerOptions;
    layerOptions.SetNameValue("SHPT", "POLYGONZ");
    layerOptions.SetNameValue("ENCODING", "UTF-8");
    layerOptions.SetNameValue("2GB_LIMIT", "YES");
    layerOptions.SetNameValue("DBF_EOF_CHAR", options.dbfEofChar ? "YES" : "NO");
    const double seconds = timeWrite(mesh, "ESRI Shapefile", shp, layerOptions, options.dbfWidth,
                                     options.dbfPrecision, options);
    removeAll(files);
    return seconds;
}

double timeMinimalFlatGeobufWrite(const TinMesh& mesh, const fs::path& dir,
                                  const MinimalWriteOptions& options) {
    const fs::path fgb = dir / "minimal.fgb";
    removeAll({fgb});
    CPLStringList layerOptions;
    layerOptions.SetNameValue("SPATIAL_INDEX", options.spatialIndex ? "YES" : "NO");
    if (!options.temporaryDir.empty())
        layerOptions.SetNameValue("TEMPORARY_DIR", options.temporaryDir.c_str());
    const double seconds = timeWrite(mesh, "FlatGeobuf", fgb, layerOptions, 0, 0, options);
    removeAll({fgb});
    return seconds;
}

} // namespace terratin::bench

#include "gpkg_tin_writer.hpp"

#include "../atomic_output.hpp"
#include "../attribute_columns.hpp"
#include "../ogr_dataset_support.hpp"
#include "../writer_support.hpp"
#include "gpkg_append.hpp"
#include "gpkg_layer_jobs.hpp"
#include "sqlite_connection.hpp"
#include "terratin/error.hpp"
#include "terratin/gdal_error.hpp"

#include <cpl_conv.h>
#include <cpl_error.h>
#include <cpl_string.h>
#include <ogrsf_frmts.h>

#include <optional>
#include <system_error>

namespace terratin::io::detail {

namespace fs = std::filesystem;

namespace {

/// The local CS that GDAL's GPKG driver files under the GeoPackage's srs_id -1.
constexpr const char* kUndefinedCartesianWkt = "LOCAL_CS[\"Undefined Cartesian SRS\"]";
/// Share of the writer's progress range for rows and index; the rest is closing and renaming.
constexpr double kWritingShare = 0.98;

/// Without a CRS, GDAL 3.6 files a GeoPackage layer under srs_id 0, "Undefined geographic
/// SRS", which tells readers the easting/northing are degrees. The GeoPackage spec's srs_id
/// -1, "Undefined Cartesian SRS", is the honest "unknown" for a DEM's planar coordinates; GDAL
/// maps this local CS to it (GDAL 3.6 has no SRID creation option).
OGRSpatialReference outputCrs(const std::string& wkt, const fs::path& output) {
    if (std::optional<OGRSpatialReference> srs = parseOutputCrs(wkt))
        return *srs;
    OGRSpatialReference undefined;
    if (undefined.importFromWkt(kUndefinedCartesianWkt) != OGRERR_NONE)
        throwGdalError(kOgrStage, "cannot set up the undefined Cartesian SRS of", output.string());
    return undefined;
}

/// A feature table with its fields, no spatial index (that comes with the rows).
void createLayer(GDALDataset& dataset, const std::string& name, OGRwkbGeometryType type,
                 OGRSpatialReference& srs,
                 const std::vector<std::pair<const char*, OGRFieldType>>& fields,
                 const fs::path& output) {
    CPLStringList layerOptions;
    layerOptions.SetNameValue("GEOMETRY_NAME", "geom");
    layerOptions.SetNameValue("FID", "fid");
    layerOptions.SetNameValue("SPATIAL_INDEX", "NO");
    CPLErrorReset();
    OGRLayer* layer = dataset.CreateLayer(name.c_str(), &srs, type, layerOptions.List());
    if (layer == nullptr)
        throwGdalError(kOgrStage, "cannot create the layer '" + name + "' of", output.string());
    for (const auto& [fieldName, fieldType] : fields) {
        OGRFieldDefn definition(fieldName, fieldType);
        if (layer->CreateField(&definition) != OGRERR_NONE)
            throwGdalError(kOgrStage, std::string("cannot create the field ") + fieldName + " of",
                           output.string());
    }
}

/// A new GeoPackage, with SQLite pages of `pageBytes`: the page size is fixed when the file
/// is created, by a pragma GDAL runs before it creates its tables.
GDALDatasetUniquePtr createGeoPackage(const fs::path& temporary, int pageBytes,
                                      const fs::path& output) {
    const std::string pragma = "page_size=" + std::to_string(pageBytes);
    CPLSetThreadLocalConfigOption("OGR_SQLITE_PRAGMA", pragma.c_str());
    try {
        GDALDatasetUniquePtr dataset = createDataset("GPKG", temporary, output);
        CPLSetThreadLocalConfigOption("OGR_SQLITE_PRAGMA", nullptr);
        // GDAL 3.6 returns the dataset even when a table of the GeoPackage's own could not be
        // created (a full disk, say); the later error, "no such table: gpkg_geometry_columns",
        // would hide that cause.
        if (CPLGetLastErrorType() == CE_Failure || CPLGetLastErrorType() == CE_Fatal)
            throwGdalError(kOgrStage, "cannot create the GeoPackage tables of", output.string());
        return dataset;
    } catch (...) {
        CPLSetThreadLocalConfigOption("OGR_SQLITE_PRAGMA", nullptr);
        throw;
    }
}

/// SQLite page size for a new file of `features`: large pages for large tables (SQLite's work
/// per page is then spread over many more rows, and inserting gets markedly faster, see
/// docs/benchmarks.md); SQLite's default for small files, which large pages would pad out
/// (every table and index takes at least one page).
int pageBytesFor(std::uint64_t features) {
    constexpr std::uint64_t kLargeTableFeatures = 65'536;
    constexpr int kLargePageBytes = 65'536;
    constexpr int kDefaultPageBytes = 4096;
    return features >= kLargeTableFeatures ? kLargePageBytes : kDefaultPageBytes;
}

} // namespace

GpkgLayerNames gpkgLayerNames(const TinWriteOptions& options) {
    return {options.layerName, options.nodes ? nodeLayerName(options.layerName) : "",
            options.edges ? edgeLayerName(options.layerName) : "", !options.vertexCells.empty()};
}

void createGpkgTinLayers(const fs::path& temporary, std::uint64_t features,
                         const GpkgLayerNames& names, const TinWriteOptions& options,
                         const fs::path& output) {
    OGRSpatialReference srs = outputCrs(options.crsWkt, output);
    GDALDatasetUniquePtr dataset = createGeoPackage(temporary, pageBytesFor(features), output);

    std::vector<std::pair<const char*, OGRFieldType>> triangleFields;
    for (const auto& column : attributeColumns(options.attributes))
        triangleFields.emplace_back(column.name, OFTReal);
    createLayer(*dataset, names.triangles, wkbPolygon25D, srs, triangleFields, output);
    if (!names.nodes.empty()) {
        std::vector<std::pair<const char*, OGRFieldType>> nodeFields{{"id", OFTInteger64}};
        if (names.nodeCells)
            nodeFields.insert(nodeFields.end(), {{"row", OFTInteger64}, {"col", OFTInteger64}});
        createLayer(*dataset, names.nodes, wkbPoint25D, srs, nodeFields, output);
    }
    if (!names.edges.empty())
        createLayer(*dataset, names.edges, wkbLineString25D, srs,
                    {{"node_from", OFTInteger64},
                     {"node_to", OFTInteger64},
                     {"tri_left", OFTInteger64},
                     {"tri_right", OFTInteger64},
                     {"length", OFTReal},
                     {"constrained", OFTInteger}},
                    output);
    closeDataset(dataset, output);
}

void configureForBulkWriting(SqliteConnection& db) {
    db.execute("PRAGMA journal_mode = OFF; PRAGMA synchronous = OFF; "
               "PRAGMA locking_mode = EXCLUSIVE; PRAGMA cache_size = -" +
               std::to_string(kGpkgPageCacheKiB));
}

void removeStaleJournals(const fs::path& output, bool replacing) {
    if (!replacing && !existingFiles({output}).empty())
        return;
    for (const char* suffix : {"-wal", "-shm", "-journal"}) {
        std::error_code error;
        fs::remove(output.string() + suffix, error);
    }
}

TinWriteResult writeGeoPackageTin(const TinMesh& mesh, const fs::path& output,
                                  const TinWriteOptions& options,
                                  const ProgressCallback& progress) {
    const std::vector<GpkgLayerJob> jobs = gpkgLayerJobs(mesh, options);
    std::uint64_t features = 0;
    for (const auto& job : jobs)
        features += job.features;
    // Progress counts rows, then index entries as much again.
    const std::uint64_t work = options.spatialIndex ? 2 * features : features;
    const ProgressTicker ticker(kOgrStage, progress, output, 0.0, kWritingShare, work);
    ticker.report(0, "Creating GeoPackage");

    if (options.appendLayer && !existingFiles({output}).empty()) {
        TinWriteResult result = appendGeoPackageTin(mesh, output, options, jobs, ticker);
        result.features = features;
        return result;
    }
    // A new file replaces only what --overwrite allows, even one that appeared while this run
    // was writing.
    const AtomicOutput temporaries(kOgrStage, output, existingTargetFor(options.overwrite));
    const fs::path temporary = temporaries.temporary(".gpkg");
    createGpkgTinLayers(temporary, features, gpkgLayerNames(options), options, output);

    TinWriteResult result;
    {
        SqliteConnection db(kOgrStage, temporary, output);
        configureForBulkWriting(db);
        db.execute("BEGIN");
        result = fillGpkgLayers(db, mesh, jobs, options.spatialIndex, ticker);
        db.execute("COMMIT");
        db.close();
    }
    // The last chance to cancel: a signal that came while SQLite committed and closed must
    // still leave the old output in place.
    ticker.reportDone("Finishing GeoPackage");

    removeStaleJournals(output, options.overwrite);
    temporaries.commit(temporary, output);
    result.features = features;
    return result;
}

} // namespace terratin::io::detail

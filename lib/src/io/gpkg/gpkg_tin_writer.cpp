#include "gpkg_tin_writer.hpp"

#include "../../stopwatch.hpp"
#include "../atomic_output.hpp"
#include "../attribute_columns.hpp"
#include "../ogr_dataset_support.hpp"
#include "../writer_support.hpp"
#include "gpkg_spatial_index.hpp"
#include "gpkg_tin_layers.hpp"
#include "sqlite_connection.hpp"
#include "terratin/error.hpp"
#include "terratin/gdal_error.hpp"

#include <cpl_conv.h>
#include <cpl_error.h>
#include <cpl_string.h>
#include <ogrsf_frmts.h>

#include <future>
#include <optional>
#include <system_error>

namespace terratin::io::detail {

namespace fs = std::filesystem;
using terratin::detail::Stopwatch;

namespace {

/// The local CS that GDAL's GPKG driver files under the GeoPackage's srs_id -1.
constexpr const char* kUndefinedCartesianWkt = "LOCAL_CS[\"Undefined Cartesian SRS\"]";
/// Share of the writer's progress range for rows and index; the rest is closing and renaming.
constexpr double kWritingShare = 0.98;
/// SQLite page cache while writing, in KiB (a negative cache_size is KiB): enough for the
/// B-tree's right edge and the index tables; the rows themselves are written once.
constexpr int kPageCacheKiB = 16 * 1024;

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

/// Opens the copy of an existing GeoPackage for update; refuses anything else.
GDALDatasetUniquePtr openGeoPackageForUpdate(const fs::path& path, const fs::path& output) {
    const char* const drivers[] = {"GPKG", nullptr};
    CPLErrorReset();
    GDALDatasetUniquePtr dataset(
        GDALDataset::Open(path.c_str(), GDAL_OF_VECTOR | GDAL_OF_UPDATE, drivers));
    if (!dataset)
        throw InvalidInputError(std::string(kOgrStage) + ": cannot add layers to " +
                                quoted(output) + ": it is not a GeoPackage GDAL can update (" +
                                lastGdalErrorMessage() + ")");
    return dataset;
}

/// Removes layer `name` when it exists and options.overwrite allows; refuses otherwise, naming
/// the options as options.optionName does.
void makeRoomForLayer(GDALDataset& dataset, const std::string& name, const TinWriteOptions& options,
                      const fs::path& output) {
    for (int i = 0; i < dataset.GetLayerCount(); ++i) {
        OGRLayer* layer = dataset.GetLayer(i);
        if (layer == nullptr || !EQUAL(layer->GetName(), name.c_str()))
            continue;
        if (!options.overwrite)
            throw InvalidInputError(std::string(kOgrStage) + ": the GeoPackage " + quoted(output) +
                                    " already has a layer '" + name + "'; choose another " +
                                    options.optionName("layer") + " or use " +
                                    options.optionName("overwrite") + " to replace it");
        if (dataset.DeleteLayer(i) != OGRERR_NONE)
            throwGdalError(kOgrStage, "cannot replace the layer '" + name + "' of",
                           output.string());
        return;
    }
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

/// One layer's rows and index, in writing order.
struct LayerJob {
    std::string name;
    std::uint64_t features = 0;
    std::string_view rowMessage;
    std::function<void(SqliteConnection&, const GpkgFeatureTable&, const RowProgress&)> rows;
    std::function<std::vector<RtreeBox>()> boxes;
};

std::vector<LayerJob> layerJobs(const TinMesh& mesh, const TinWriteOptions& options,
                                const GpkgLayerNames& names) {
    std::vector<LayerJob> jobs;
    jobs.push_back(
        {names.triangles, mesh.triangleCount(), "Writing triangles",
         [&](SqliteConnection& db, const GpkgFeatureTable& table, const RowProgress& progress) {
             insertTriangleRows(db, table, mesh, options.attributes, 1, progress);
         },
         [&] { return triangleBoxes(mesh); }});
    if (!names.nodes.empty())
        jobs.push_back(
            {names.nodes, mesh.vertexCount(), "Writing nodes",
             [&](SqliteConnection& db, const GpkgFeatureTable& table, const RowProgress& progress) {
                 insertNodeRows(db, table, mesh, options.vertexCells, 1, progress);
             },
             [&] { return nodeBoxes(mesh); }});
    if (!names.edges.empty())
        jobs.push_back(
            {names.edges, edgeCount(mesh), "Writing edges",
             [&](SqliteConnection& db, const GpkgFeatureTable& table, const RowProgress& progress) {
                 insertEdgeRows(db, table, mesh, options.constrainedEdges, progress);
             },
             [&] { return edgeBoxes(mesh); }});
    return jobs;
}

/// SQLite's part: every layer's rows, then every layer's spatial index, in one transaction.
/// Returns the seconds each took.
TinWriteResult fillTables(const fs::path& temporary, const fs::path& output, const TinMesh& mesh,
                          const std::vector<LayerJob>& jobs, bool spatialIndex,
                          const ProgressTicker& ticker) {
    TinWriteResult result;
    SqliteConnection db(kOgrStage, temporary, output);
    configureForBulkWriting(db);
    const int capacity = rtreeNodeCapacity(static_cast<int>(db.queryInteger("PRAGMA page_size")));
    db.execute("BEGIN");

    // The triangles' tree is packed on another thread while the rows go in.
    std::future<PackedRtree> firstTree;
    if (spatialIndex)
        firstTree = std::async(std::launch::async,
                               [&] { return PackedRtree(jobs.front().boxes(), capacity); });

    const Extent2d extent = meshExtent(mesh);
    const Stopwatch rowsTime;
    std::uint64_t done = 0;
    for (const auto& job : jobs) {
        GpkgFeatureTable table(db, job.name);
        job.rows(db, table,
                 [&](std::uint64_t rows) { ticker.report(done + rows, job.rowMessage); });
        table.finish(job.features, extent);
        done += job.features;
    }
    result.rowSeconds = rowsTime.seconds();

    const Stopwatch indexTime;
    for (std::size_t i = 0; spatialIndex && i < jobs.size(); ++i) {
        const PackedRtree tree = i == 0 ? firstTree.get() : PackedRtree(jobs[i].boxes(), capacity);
        writeGpkgSpatialIndex(db, {jobs[i].name, "geom", "fid"}, tree, [&](std::uint64_t entries) {
            ticker.report(done + entries, "Building spatial index");
        });
        done += jobs[i].features;
    }
    result.indexSeconds = indexTime.seconds();
    db.execute("COMMIT");
    db.close();
    return result;
}

} // namespace

GpkgLayerNames gpkgLayerNames(const TinWriteOptions& options) {
    return {options.layerName, options.nodes ? nodeLayerName(options.layerName) : "",
            options.edges ? edgeLayerName(options.layerName) : "", !options.vertexCells.empty()};
}

void createGpkgTinLayers(const fs::path& temporary, bool appending, std::uint64_t features,
                         const GpkgLayerNames& names, const TinWriteOptions& options,
                         const fs::path& output) {
    OGRSpatialReference srs = outputCrs(options.crsWkt, output);
    GDALDatasetUniquePtr dataset =
        appending ? openGeoPackageForUpdate(temporary, output)
                  : createGeoPackage(temporary, pageBytesFor(features), output);
    if (appending)
        for (const std::string* name : {&names.triangles, &names.nodes, &names.edges})
            if (!name->empty())
                makeRoomForLayer(*dataset, *name, options, output);

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
               std::to_string(kPageCacheKiB));
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
    const GpkgLayerNames names = gpkgLayerNames(options);
    const std::vector<LayerJob> jobs = layerJobs(mesh, options, names);
    std::uint64_t features = 0;
    for (const auto& job : jobs)
        features += job.features;
    // Progress counts rows, then index entries as much again.
    const std::uint64_t work = options.spatialIndex ? 2 * features : features;
    const ProgressTicker ticker(kOgrStage, progress, output, 0.0, kWritingShare, work);
    ticker.report(0, "Creating GeoPackage");

    const bool appending = options.appendLayer && !existingFiles({output}).empty();
    // The copy extended with new layers replaces the original by design; a new file replaces
    // only what --overwrite allows, even one that appeared while this run was writing.
    const AtomicOutput temporaries(kOgrStage, output,
                                   appending ? ExistingTarget::Replace
                                             : existingTargetFor(options.overwrite),
                                   options.optionName);
    const fs::path temporary = temporaries.temporary(".gpkg");
    if (appending) {
        std::error_code error;
        fs::copy_file(output, temporary, error);
        if (error)
            throw IoError(std::string(kOgrStage) + ": cannot copy " + quoted(output) +
                          " to add layers to it: " + error.message());
    }
    createGpkgTinLayers(temporary, appending, features, names, options, output);

    TinWriteResult result = fillTables(temporary, output, mesh, jobs, options.spatialIndex, ticker);
    // The last chance to cancel: a signal that came while SQLite committed and closed must
    // still leave the old output in place.
    ticker.report(work, "Finishing GeoPackage");

    removeStaleJournals(output, appending || options.overwrite);
    temporaries.commit(temporary, output);
    result.features = features;
    return result;
}

} // namespace terratin::io::detail

/// @file
/// OgrTinWriter: a TinMesh as Polygon Z triangles through OGR (GeoPackage or ESRI Shapefile).
///
/// Atomicity. Everything is written under a temporary name in the output's own directory
/// (same file system, so the final rename(2) is atomic and never copies): a GeoPackage as
/// ".<stem>.tmp-<pid>-<random>.gpkg", a Shapefile as the files of a temporary directory
/// ".<stem>.tmp-<pid>-<random>/". Every directory entry whose name starts with that prefix
/// (including SQLite journals and the background R-tree database that newer GDAL versions
/// create as "<temporary>.gpkg.tmp_rtree_<layer>.db") is removed on the way out, whatever
/// happens.
/// A GeoPackage replaces an existing output in one rename. A Shapefile is several files; they
/// are renamed one at a time, .shp last, so readers can briefly see a mixed set while an
/// existing output is overwritten. That is the format's limit, not something a writer can fix.
///
/// Speed. GeoPackage features are inserted in one transaction, and the R-tree is not
/// maintained per insert: for a layer created in the same dataset, GDAL's GPKG driver defers
/// the spatial index and fills it in one pass when the layer is synced (debug line "N rows
/// inserted into rtree_..."). No GeoPackage SQL is written here; GDAL owns the format.
///
/// Why one transaction rather than a commit every 100k features: the deferred R-tree is built
/// over every committed row when the dataset closes, even on the failure path where the file
/// is deleted next (GDALDataset::DeleteLayer builds it too). With a commit per 100k features
/// (measured, 1.5 M triangles) a Ctrl-C late in the write waited 25-45 s for an index nobody
/// would read; with one transaction it rolls back in milliseconds. The cost is nil: in a new
/// database SQLite journals only the pages that existed when the transaction began (the
/// journal stays at ~45 kB for 1.5 M triangles), and dirty pages spill to the file as the
/// cache fills, so memory stays flat.
///
/// GDAL 3.6 can also bulk-load the R-tree in a background thread
/// (OGR_GPKG_ALLOW_THREADED_RTREE), but only when the dataset already counts one layer as the
/// new one is set up. Checked in Debian's 3.6.2 (the test is `m_nLayers == 1`, made before
/// the new layer is appended): for the first layer of a new file it never engages, and the
/// one-pass SQLite R*-tree insertion is about 85 % of the GeoPackage time at 1.5 M triangles.
/// Later GDAL releases test for 0 layers instead and build the index alongside the inserts;
/// this code needs no change for that. One OGRFeature and one polygon serve every triangle.
///
/// A Shapefile's layer is named after its file; TinWriteOptions::layerName applies to
/// GeoPackage only.

#include "terratin/io/tin_writer.hpp"

#include "terratin/error.hpp"
#include "terratin/geometry/triangle_attributes.hpp"
#include "terratin/io/gdal_error.hpp"

#include <cpl_conv.h>
#include <cpl_error.h>
#include <gdal_priv.h>
#include <ogr_feature.h>
#include <ogr_geometry.h>
#include <ogr_spatialref.h>
#include <ogrsf_frmts.h>

#include <unistd.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <optional>
#include <random>
#include <sstream>
#include <string_view>
#include <system_error>
#include <vector>

namespace terratin::io {

namespace fs = std::filesystem;

namespace {

constexpr std::string_view kStage = "OgrTinWriter";

/// Features between two progress reports: frequent enough for a responsive Ctrl-C (a few
/// tenths of a second), rare enough that the callback costs nothing measurable.
constexpr std::size_t kProgressInterval = 65'536;

/// Share of the progress range given to inserting features; the rest is the spatial index
/// (GeoPackage) or closing the files (Shapefile), then the rename into place. Measured with
/// GDAL 3.6.2 on 1.5 M triangles: the GeoPackage R-tree, built in one uninterruptible call,
/// takes about 80 % of the time; a Shapefile is all feature writing.
constexpr double kGeoPackageFeatureShare = 0.2;
constexpr double kShapefileFeatureShare = 0.98;

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

/// Sidecar extensions another tool may have left next to an old Shapefile of the same name;
/// they describe the old geometry (spatial indexes, metadata) and are stale once it is
/// replaced.
constexpr std::array<std::string_view, 11> kShapefileSidecars = {
    ".prj", ".cpg", ".qix", ".sbn", ".sbx", ".fix", ".qpj", ".shp.xml", ".aih", ".ain", ".atx"};

/// The local CS that GDAL's GPKG driver files under the GeoPackage's srs_id -1.
constexpr const char* kUndefinedCartesianWkt = "LOCAL_CS[\"Undefined Cartesian SRS\"]";

/// The attribute columns, in order.
struct AttributeField {
    const char* name;
    double TriangleAttributes::*member;
};
constexpr std::array<AttributeField, 6> kAttributeFields = {{
    {"z_min", &TriangleAttributes::zMin},
    {"z_max", &TriangleAttributes::zMax},
    {"z_mean", &TriangleAttributes::zMean},
    {"slope_deg", &TriangleAttributes::slopeDeg},
    {"aspect_deg", &TriangleAttributes::aspectDeg},
    {"area_2d", &TriangleAttributes::area2d},
}};

std::string toLower(std::string_view text) {
    std::string lower(text);
    std::transform(lower.begin(), lower.end(), lower.begin(),
                   [](unsigned char ch) { return static_cast<char>(std::tolower(ch)); });
    return lower;
}

std::string quoted(const fs::path& path) {
    // Appended piecewise: GCC 12 reports a spurious -Wrestrict for "'" + string + "'".
    std::string text = "'";
    text += path.string();
    text += '\'';
    return text;
}

[[noreturn]] void throwIo(const std::string& message) {
    throw IoError(std::string(kStage) + ": " + message);
}

[[noreturn]] void throwInvalid(const std::string& message) {
    throw InvalidInputError(std::string(kStage) + ": " + message);
}

/// Removes, on destruction, every entry of `directory` whose name starts with `prefix`.
/// The prefix holds the process id and 64 random bits, so it names only this run's files.
class TemporaryEntries {
public:
    TemporaryEntries(fs::path directory, std::string prefix)
        : m_directory(std::move(directory)), m_prefix(std::move(prefix)) {}
    TemporaryEntries(const TemporaryEntries&) = delete;
    TemporaryEntries& operator=(const TemporaryEntries&) = delete;
    ~TemporaryEntries() { removeAll(); }

    [[nodiscard]] fs::path path(std::string_view suffix = {}) const {
        return m_directory / (m_prefix + std::string(suffix));
    }

private:
    // Never throws: it runs while an exception is already propagating.
    void removeAll() noexcept {
        try {
            std::error_code error;
            std::vector<fs::path> doomed;
            for (fs::directory_iterator it(m_directory, error), end; !error && it != end;
                 it.increment(error)) {
                if (it->path().filename().string().starts_with(m_prefix))
                    doomed.push_back(it->path());
            }
            for (const auto& entry : doomed)
                fs::remove_all(entry, error);
        } catch (...) {
            // Out of memory while listing: nothing sensible left to do in a destructor.
        }
    }

    fs::path m_directory;
    std::string m_prefix;
};

std::string temporaryPrefix(const fs::path& output) {
    std::random_device device;
    const std::uint64_t random =
        (static_cast<std::uint64_t>(device()) << 32U) ^ static_cast<std::uint64_t>(device());
    std::ostringstream prefix;
    prefix << '.' << output.stem().string() << ".tmp-" << ::getpid() << '-' << std::hex << random;
    return prefix.str();
}

fs::path outputDirectory(const fs::path& output) {
    return output.has_parent_path() ? output.parent_path() : fs::path(".");
}

/// Path of the Shapefile component `extension` (".dbf"...) of `shp`, in the case of the
/// .shp's own extension (GDAL and other readers look for "X.DBF" next to "X.SHP").
fs::path shapefileComponent(const fs::path& shp, std::string_view extension) {
    std::string ext(extension);
    const std::string shpExt = shp.extension().string();
    if (!shpExt.empty() && std::all_of(shpExt.begin() + 1, shpExt.end(),
                                       [](unsigned char ch) { return std::isupper(ch) != 0; }))
        std::transform(ext.begin(), ext.end(), ext.begin(),
                       [](unsigned char ch) { return static_cast<char>(std::toupper(ch)); });
    fs::path component = shp;
    component.replace_extension();
    return component.string() + ext;
}

void checkMesh(const TinMesh& mesh, const fs::path& output) {
    if (mesh.triangles.size() % 3 != 0)
        throwInvalid("the mesh's triangle array has " + std::to_string(mesh.triangles.size()) +
                     " entries, not a multiple of 3; nothing written to " + quoted(output));
    if (mesh.triangleCount() == 0)
        throwInvalid("the mesh has no triangles; nothing written to " + quoted(output));
    const std::size_t vertexCount = mesh.vertexCount();
    for (std::size_t i = 0; i < mesh.triangles.size(); ++i) {
        if (mesh.triangles[i] >= vertexCount)
            throwInvalid("triangle " + std::to_string(i / 3) + " refers to vertex " +
                         std::to_string(mesh.triangles[i]) + " of " + std::to_string(vertexCount) +
                         "; nothing written to " + quoted(output));
    }
}

void checkShapefileSize(std::size_t triangleCount, const fs::path& output) {
    const auto count = static_cast<std::uint64_t>(triangleCount);
    const std::uint64_t shpBytes = kShpHeaderBytes + count * kShpRecordBytes;
    // .dbf: 32-byte header, 32 bytes per field descriptor, a terminator, one deletion flag
    // plus the fixed-width columns per record, and an end-of-file marker.
    const std::uint64_t dbfBytes =
        32 + 32 * kAttributeFields.size() + 1 +
        count * (1 + kAttributeFields.size() * static_cast<std::uint64_t>(kDbfRealWidth)) + 1;
    const std::uint64_t largest = std::max(shpBytes, dbfBytes);
    if (largest > kShapefileMaxBytes)
        throwInvalid(std::to_string(triangleCount) + " triangles need about " +
                     std::to_string(largest / (1024 * 1024)) +
                     " MiB per Shapefile component, over the format's 2 GB limit; write a "
                     "GeoPackage (.gpkg) instead of " +
                     quoted(output));
}

std::optional<OGRSpatialReference> parseCrs(const std::string& wkt) {
    if (wkt.empty())
        return std::nullopt;
    std::optional<OGRSpatialReference> srs(std::in_place);
    if (srs->importFromWkt(wkt.c_str()) != OGRERR_NONE)
        throw CrsError(std::string(kStage) +
                       ": the output CRS is not valid WKT: " + lastGdalErrorMessage());
    // x = easting, y = northing whatever the CRS's declared axis order: that is how the mesh
    // stores its coordinates.
    srs->SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
    return srs;
}

/// Any of these existing counts as "the output exists".
std::vector<fs::path> existingOutputFiles(const fs::path& output, TinFormat format) {
    std::vector<fs::path> candidates{output};
    if (format == TinFormat::Shapefile) {
        candidates.push_back(shapefileComponent(output, ".shx"));
        candidates.push_back(shapefileComponent(output, ".dbf"));
    }
    std::vector<fs::path> existing;
    for (const auto& candidate : candidates) {
        std::error_code error;
        if (fs::exists(fs::symlink_status(candidate, error)))
            existing.push_back(candidate);
    }
    return existing;
}

void checkOutputPath(const fs::path& output, const TinWriteOptions& options) {
    std::error_code error;
    if (output.filename().empty() || output.filename() == "." || output.filename() == "..")
        throwInvalid("the output " + quoted(output) + " names no file");
    if (options.format == TinFormat::Shapefile && toLower(output.extension().string()) != ".shp")
        throwInvalid("a Shapefile output must end in .shp, not " + quoted(output));
    if (fs::is_directory(output, error))
        throwIo("the output " + quoted(output) + " is a directory, not a file");

    const fs::path directory = outputDirectory(output);
    const auto status = fs::status(directory, error);
    if (!fs::exists(status))
        throwIo("the output directory " + quoted(directory) + " does not exist");
    if (!fs::is_directory(status))
        throwIo("the output's parent " + quoted(directory) + " is not a directory");
    // Write and search permission are both needed to create and rename entries.
    if (::access(directory.c_str(), W_OK | X_OK) != 0)
        throwIo("the output directory " + quoted(directory) +
                " is not writable: " + std::strerror(errno));

    const auto existing = existingOutputFiles(output, options.format);
    if (!existing.empty() && !options.overwrite)
        throwInvalid("the output " + quoted(existing.front()) + " exists; use --overwrite");
    for (const auto& file : existing) {
        if (fs::is_directory(file, error))
            throwIo("the output " + quoted(file) + " is a directory, not a file");
    }
}

void reportProgress(const ProgressCallback& progress, double fraction, std::string_view message,
                    const fs::path& output) {
    if (progress && !progress(fraction, message))
        throw Cancelled(std::string(kStage) + ": cancelled; " + quoted(output) +
                        " was not written");
}

/// Closes the dataset and turns a failure while flushing (disk full...) into IoError.
/// GDAL 3.6's GDALClose reports nothing, so the error state is the only witness.
void closeDataset(GDALDatasetUniquePtr& dataset, const fs::path& output) {
    CPLErrorReset();
    dataset.reset();
    if (CPLGetLastErrorType() == CE_Failure || CPLGetLastErrorType() == CE_Fatal)
        throwGdalError(kStage, "cannot finish writing", output.string());
}

GDALDatasetUniquePtr createDataset(const char* driverName, const fs::path& path,
                                   const fs::path& output) {
    GDALDriver* driver = GetGDALDriverManager()->GetDriverByName(driverName);
    if (driver == nullptr)
        throwIo(std::string("GDAL has no '") + driverName + "' driver, needed for " +
                quoted(output));
    CPLErrorReset();
    GDALDatasetUniquePtr dataset(driver->Create(path.c_str(), 0, 0, 0, GDT_Unknown, nullptr));
    if (!dataset)
        throwGdalError(kStage, "cannot create a temporary file for", output.string());
    return dataset;
}

OGRLayer* createLayer(GDALDataset& dataset, const std::string& layerName,
                      std::optional<OGRSpatialReference>& srs, TinFormat format,
                      const fs::path& output) {
    CPLStringList layerOptions;
    if (format == TinFormat::GeoPackage) {
        layerOptions.SetNameValue("GEOMETRY_NAME", "geom");
        layerOptions.SetNameValue("FID", "fid");
        layerOptions.SetNameValue("SPATIAL_INDEX", "YES");
    } else {
        layerOptions.SetNameValue("SHPT", "POLYGONZ");
        layerOptions.SetNameValue("ENCODING", "UTF-8");
        // Backstop for the up-front size check: GDAL would otherwise grow files to 4 GB.
        layerOptions.SetNameValue("2GB_LIMIT", "YES");
    }
    CPLErrorReset();
    OGRLayer* layer = dataset.CreateLayer(layerName.c_str(), srs ? &*srs : nullptr, wkbPolygon25D,
                                          layerOptions.List());
    if (layer == nullptr)
        throwGdalError(kStage, "cannot create the triangle layer of", output.string());

    for (const auto& field : kAttributeFields) {
        OGRFieldDefn definition(field.name, OFTReal);
        if (format == TinFormat::Shapefile) {
            definition.SetWidth(kDbfRealWidth);
            definition.SetPrecision(kDbfRealPrecision);
        }
        if (layer->CreateField(&definition) != OGRERR_NONE)
            throwGdalError(kStage, std::string("cannot create the field ") + field.name + " of",
                           output.string());
    }
    return layer;
}

/// Inserts one feature per triangle, then reports `finishing` (the last chance to cancel).
/// GeoPackage inserts run in one transaction, committed only after that report, so that any
/// exception up to then rolls every insert back.
void writeFeatures(GDALDataset& dataset, OGRLayer& layer, const TinMesh& mesh, TinFormat format,
                   const ProgressCallback& progress, std::string_view finishing,
                   const fs::path& output) {
    const OGRFeatureDefn* definition = layer.GetLayerDefn();
    std::array<int, kAttributeFields.size()> fieldIndex{};
    for (std::size_t i = 0; i < kAttributeFields.size(); ++i) {
        fieldIndex[i] = definition->GetFieldIndex(kAttributeFields[i].name);
        if (fieldIndex[i] < 0)
            throwIo(std::string("the driver did not keep the field ") + kAttributeFields[i].name +
                    " in " + quoted(output));
    }

    // One feature and one polygon for all triangles: the ring's 4 points are overwritten in
    // place, so no geometry is allocated per triangle.
    OGRFeatureUniquePtr feature(OGRFeature::CreateFeature(layer.GetLayerDefn()));
    auto* ring = new OGRLinearRing();
    for (int i = 0; i < 4; ++i)
        ring->setPoint(i, 0.0, 0.0, 0.0);
    auto* polygon = new OGRPolygon();
    polygon->addRingDirectly(ring);
    polygon->set3D(TRUE);
    feature->SetGeometryDirectly(polygon);

    const bool useTransaction = format == TinFormat::GeoPackage;
    const double featureShare =
        format == TinFormat::GeoPackage ? kGeoPackageFeatureShare : kShapefileFeatureShare;
    if (useTransaction && dataset.StartTransaction() != OGRERR_NONE)
        throwGdalError(kStage, "cannot start a transaction in", output.string());

    const std::size_t triangleCount = mesh.triangleCount();
    try {
        for (std::size_t t = 0; t < triangleCount; ++t) {
            if (t % kProgressInterval == 0)
                reportProgress(progress,
                               featureShare * static_cast<double>(t) /
                                   static_cast<double>(triangleCount),
                               "Writing triangles", output);

            const Point3& a = mesh.vertices[mesh.triangles[3 * t]];
            const Point3& b = mesh.vertices[mesh.triangles[3 * t + 1]];
            const Point3& c = mesh.vertices[mesh.triangles[3 * t + 2]];
            ring->setPoint(0, a.x, a.y, a.z);
            ring->setPoint(1, b.x, b.y, b.z);
            ring->setPoint(2, c.x, c.y, c.z);
            ring->setPoint(3, a.x, a.y, a.z);

            const TriangleAttributes attributes = computeTriangleAttributes(a, b, c);
            for (std::size_t i = 0; i < kAttributeFields.size(); ++i) {
                const double value = attributes.*(kAttributeFields[i].member);
                if (format == TinFormat::Shapefile && !(std::fabs(value) < kDbfMaxMagnitude))
                    throwInvalid("triangle " + std::to_string(t) + " has " +
                                 kAttributeFields[i].name + " = " + std::to_string(value) +
                                 ", which does not fit a Shapefile's DBF column; write a "
                                 "GeoPackage (.gpkg) instead of " +
                                 quoted(output));
                feature->SetField(fieldIndex[i], value);
            }

            // CreateFeature stores the new FID in the feature; a reused feature must be reset
            // or the next insert would collide with it.
            feature->SetFID(OGRNullFID);
            if (layer.CreateFeature(feature.get()) != OGRERR_NONE)
                throwGdalError(kStage, "cannot write triangle " + std::to_string(t) + " to",
                               output.string());
        }
        reportProgress(progress, featureShare, finishing, output);
    } catch (...) {
        if (useTransaction)
            dataset.RollbackTransaction();
        throw;
    }
    if (useTransaction && dataset.CommitTransaction() != OGRERR_NONE)
        throwGdalError(kStage, "cannot commit the triangles to", output.string());
}

void writeGeoPackage(const TinMesh& mesh, const fs::path& output, const TinWriteOptions& options,
                     std::optional<OGRSpatialReference>& srs, const ProgressCallback& progress) {
    // Without a CRS, GDAL 3.6 files a GeoPackage layer under srs_id 0, "Undefined geographic
    // SRS", which tells readers the easting/northing are degrees. The GeoPackage spec's
    // srs_id -1, "Undefined Cartesian SRS", is the honest "unknown" for a DEM's planar
    // coordinates; GDAL maps this local CS to it (GDAL 3.6 has no SRID creation option).
    if (!srs) {
        srs.emplace();
        if (srs->importFromWkt(kUndefinedCartesianWkt) != OGRERR_NONE)
            throwGdalError(kStage, "cannot set up the undefined Cartesian SRS of", output.string());
    }
    const TemporaryEntries temporaries(outputDirectory(output), temporaryPrefix(output));
    const fs::path temporary = temporaries.path(".gpkg");
    {
        GDALDatasetUniquePtr dataset = createDataset("GPKG", temporary, output);
        OGRLayer* layer = createLayer(*dataset, options.layerName, srs, options.format, output);
        writeFeatures(*dataset, *layer, mesh, options.format, progress, "Building spatial index",
                      output);
        // Builds the deferred R-tree and writes the extent now, where a failure can still be
        // reported, rather than silently inside the dataset's destructor.
        CPLErrorReset();
        if (layer->SyncToDisk() != OGRERR_NONE)
            throwGdalError(kStage, "cannot build the spatial index of", output.string());
        closeDataset(dataset, output);
    }

    // A journal or WAL left by an earlier SQLite session on the old output would be replayed
    // into the new file under the same name and corrupt it: remove them before the rename.
    for (const char* suffix : {"-wal", "-shm", "-journal"}) {
        std::error_code error;
        fs::remove(output.string() + suffix, error);
    }
    std::error_code error;
    fs::rename(temporary, output, error);
    if (error)
        throwIo("cannot move the finished GeoPackage to " + quoted(output) + ": " +
                error.message());
}

void writeShapefile(const TinMesh& mesh, const fs::path& output, const TinWriteOptions& options,
                    std::optional<OGRSpatialReference>& srs, const ProgressCallback& progress) {
    const TemporaryEntries temporaries(outputDirectory(output), temporaryPrefix(output));
    const fs::path temporaryDirectory = temporaries.path();
    std::error_code error;
    if (!fs::create_directory(temporaryDirectory, error) || error)
        throwIo("cannot create the temporary directory " + quoted(temporaryDirectory) + ": " +
                (error ? error.message() : std::string("it exists")));

    // Lower-case names inside the temporary directory; shapefileComponent gives the final
    // names the case of the requested .shp.
    const std::string stem = output.stem().string();
    const fs::path temporaryShp = temporaryDirectory / (stem + ".shp");
    {
        GDALDatasetUniquePtr dataset = createDataset("ESRI Shapefile", temporaryShp, output);
        OGRLayer* layer = createLayer(*dataset, stem, srs, options.format, output);
        writeFeatures(*dataset, *layer, mesh, options.format, progress, "Finishing Shapefile",
                      output);
        closeDataset(dataset, output);
    }

    // Every file GDAL wrote, by its extension after the stem (".shp", ".shx", ".dbf", ".prj",
    // ".cpg").
    std::vector<std::string> written;
    for (fs::directory_iterator it(temporaryDirectory, error), end; !error && it != end;
         it.increment(error)) {
        const std::string name = it->path().filename().string();
        if (name.starts_with(stem) && name.size() > stem.size())
            written.push_back(name.substr(stem.size()));
    }
    if (error)
        throwIo("cannot list the temporary directory " + quoted(temporaryDirectory) + ": " +
                error.message());
    // The .shp goes last: readers find a Shapefile through it.
    std::stable_partition(written.begin(), written.end(),
                          [](const std::string& ext) { return toLower(ext) != ".shp"; });
    for (const auto& ext : written) {
        const fs::path target = shapefileComponent(output, toLower(ext));
        fs::rename(temporaryDirectory / (stem + ext), target, error);
        if (error)
            throwIo("cannot move the finished Shapefile component to " + quoted(target) + ": " +
                    error.message());
    }

    for (const auto& sidecar : kShapefileSidecars) {
        const bool rewritten = std::any_of(written.begin(), written.end(), [&](const auto& ext) {
            return toLower(ext) == sidecar;
        });
        if (!rewritten)
            fs::remove(shapefileComponent(output, sidecar), error);
    }
}

} // namespace

TinFormat parseTinFormat(const std::string& name) {
    const std::string lower = toLower(name);
    if (lower == "gpkg" || lower == "geopackage")
        return TinFormat::GeoPackage;
    if (lower == "shp" || lower == "esri shapefile")
        return TinFormat::Shapefile;
    throwInvalid("unknown output format '" + name + "'; use GPKG or SHP");
}

TinFormat tinFormatFromPath(const fs::path& path) {
    const std::string extension = toLower(path.extension().string());
    if (extension == ".gpkg")
        return TinFormat::GeoPackage;
    if (extension == ".shp")
        return TinFormat::Shapefile;
    throwInvalid("cannot tell the output format of " + quoted(path) +
                 " from its extension; use .gpkg or .shp");
}

void writeTin(const TinMesh& mesh, const fs::path& output, const TinWriteOptions& options,
              const ProgressCallback& progress) {
    initialiseGdal();

    // Everything that can be refused is refused before the first byte is written.
    checkMesh(mesh, output);
    if (options.format == TinFormat::Shapefile)
        checkShapefileSize(mesh.triangleCount(), output);
    std::optional<OGRSpatialReference> srs = parseCrs(options.crsWkt);
    checkOutputPath(output, options);

    if (options.format == TinFormat::GeoPackage)
        writeGeoPackage(mesh, output, options, srs, progress);
    else
        writeShapefile(mesh, output, options, srs, progress);

    // The output is complete and in place: there is nothing left to cancel.
    if (progress)
        progress(1.0, "Done");
}

} // namespace terratin::io

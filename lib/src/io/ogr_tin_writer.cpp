/// @file
/// OgrTinWriter: Shapefile and FlatGeobuf through OGR; GeoPackage is gpkg/gpkg_tin_writer.cpp.
///
/// Atomicity: see atomic_output.hpp. A Shapefile is several files; they are renamed one at a
/// time, .shp last, so readers can briefly see a mixed set while an existing output is
/// overwritten. That is the format's limit, not something a writer can fix. Without
/// --overwrite, a component that another program created during the run refuses the whole set,
/// and the components already renamed are taken back.
///
/// One OGRFeature and one polygon are reused for all triangles (the ring's points are
/// overwritten in place, nothing is allocated per triangle); attributes are computed with TBB
/// a chunk ahead of the inserts. Measured figures are in docs/benchmarks.md.
///
/// FlatGeobuf's packed Hilbert R-tree is built by GDAL when the file is closed: it keeps every
/// feature in a temporary file, sorts them along a Hilbert curve (recomputing both keys in
/// every comparison, a cost no input order removes) and copies them into the output. Two
/// things are ours to choose. The temporary file goes to /vsimem/ (layer creation option
/// TEMPORARY_DIR) when it fits comfortably in memory, which spares writing and reading it back
/// through the kernel; larger outputs keep it on disk. And the triangles are handed over
/// already in the order the index stores them (packed_rtree_order.hpp), so that the sort and
/// the copy walk memory in order. The sort itself stays GDAL's and bounds the speed;
/// TinWriteOptions::spatialIndex = false streams the file directly.
///
/// A Shapefile's time goes to the DBF: shapelib formats every attribute with printf
/// ("%24.12f"), which no option changes. What an option does change: by default shapelib
/// writes the DBF end-of-file mark (0x1A) after each record and seeks back over it before the
/// next, and each such seek makes stdio read the file's current block back (a seek, a 4 KiB
/// read and a write per record). The layer is therefore created with DBF_EOF_CHAR=NO, and the
/// last triangle appended in a second session opened with DBF_EOF_CHAR=YES, which writes the
/// mark: the files are the same bytes as a single session's.
///
/// A Shapefile's and a FlatGeobuf's layer is named after its file; TinWriteOptions::layerName
/// applies to GeoPackage only.

#include "ogr_tin_writer.hpp"

#include "atomic_output.hpp"
#include "attribute_columns.hpp"
#include "chunk_pipeline.hpp"
#include "gpkg/gpkg_tin_writer.hpp"
#include "ogr_dataset_support.hpp"
#include "packed_rtree_order.hpp"
#include "terratin/error.hpp"
#include "terratin/gdal_error.hpp"
#include "terratin/text.hpp"
#include "writer_support.hpp"

#include <cpl_conv.h>
#include <cpl_error.h>
#include <gdal_priv.h>
#include <ogr_feature.h>
#include <ogr_geometry.h>
#include <ogr_spatialref.h>
#include <ogrsf_frmts.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <string_view>
#include <system_error>
#include <vector>

namespace terratin::io::detail {

namespace fs = std::filesystem;

namespace {

constexpr std::string_view kStage = kOgrStage;

/// Share of the writer's progress range given to inserting features; the rest is closing the
/// dataset (FlatGeobuf builds its index then) and the rename.
constexpr double kInsertShareWithoutIndex = 0.98;

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

/// FlatGeobuf: bytes GDAL keeps per triangle in its temporary file, an upper estimate: the
/// size prefix, the feature and geometry tables and the xy and z vectors (about 160 bytes),
/// plus a column index and a double per attribute. Measured: about 300 bytes with 14 columns.
constexpr std::uint64_t kFgbFeatureBytes = 176;
constexpr std::uint64_t kFgbColumnBytes = 10;
/// The temporary file goes to memory only while it takes at most this share of the RAM GDAL
/// reports usable: it comes on top of the mesh, GDAL's own index entries (about 100 bytes per
/// feature) and whatever the caller holds.
constexpr std::uint64_t kFgbInMemoryRamDivisor = 4;

/// Sidecar extensions another tool may have left next to an old Shapefile of the same name;
/// they describe the old data set (CRS, encoding, spatial indexes, metadata, QGIS's style)
/// and are stale once it is replaced. Each one counts as the output existing: without
/// --overwrite none is touched, even when it belongs to a raster of the same name (an ESRI
/// grid's .prj; issue 22, D1).
constexpr std::array<std::string_view, 12> kShapefileSidecars = {".prj", ".cpg", ".qix", ".sbn",
                                                                 ".sbx", ".fix", ".qpj", ".shp.xml",
                                                                 ".aih", ".ain", ".atx", ".qml"};

[[noreturn]] void throwIo(const std::string& message) {
    throw IoError(std::string(kStage) + ": " + message);
}

[[noreturn]] void throwInvalid(const std::string& message) {
    throw InvalidInputError(std::string(kStage) + ": " + message);
}

std::string toUpper(std::string_view text) {
    std::string upper(text);
    std::transform(upper.begin(), upper.end(), upper.begin(),
                   [](unsigned char ch) { return static_cast<char>(std::toupper(ch)); });
    return upper;
}

/// `shp` with its extension replaced by `extension` as given.
fs::path withExtension(const fs::path& shp, std::string_view extension) {
    fs::path component = shp;
    component.replace_extension();
    return component.string() + std::string(extension);
}

/// Path of the Shapefile component `extension` (".dbf"...) of `shp`, in the case of the
/// .shp's own extension (GDAL and other readers look for "X.DBF" next to "X.SHP").
fs::path shapefileComponent(const fs::path& shp, std::string_view extension) {
    const std::string shpExt = shp.extension().string();
    const bool upper =
        !shpExt.empty() && std::all_of(shpExt.begin() + 1, shpExt.end(),
                                       [](unsigned char ch) { return std::isupper(ch) != 0; });
    return withExtension(shp, upper ? toUpper(extension) : std::string(extension));
}

/// The component `extension` of `shp` in both cases: readers find "X.PRJ" next to "x.shp"
/// too, so either one belongs to the Shapefile.
std::vector<fs::path> shapefileComponentsAnyCase(const fs::path& shp, std::string_view extension) {
    std::vector<fs::path> paths{withExtension(shp, lowercase(extension))};
    if (toUpper(extension) != lowercase(extension))
        paths.push_back(withExtension(shp, toUpper(extension)));
    return paths;
}

struct LayerSpec {
    std::string name;
    OGRwkbGeometryType type;
    TinFormat format;
    /// FlatGeobuf with a spatial index: TEMPORARY_DIR, empty for GDAL's default (the output's
    /// directory).
    std::string temporaryDirectory = {};
};

OGRLayer* createLayer(GDALDataset& dataset, const LayerSpec& spec,
                      std::optional<OGRSpatialReference>& srs, const TinWriteOptions& options,
                      const fs::path& output) {
    CPLStringList layerOptions;
    switch (spec.format) {
    case TinFormat::Shapefile:
        layerOptions.SetNameValue("SHPT", spec.type == wkbPolygon25D ? "POLYGONZ" : "ARCZ");
        layerOptions.SetNameValue("ENCODING", "UTF-8");
        // Backstop for the up-front size check: GDAL would otherwise grow files to 4 GB.
        layerOptions.SetNameValue("2GB_LIMIT", "YES");
        // The end-of-file mark is written by a second session (see the file comment).
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
    OGRLayer* layer = dataset.CreateLayer(spec.name.c_str(), srs ? &*srs : nullptr, spec.type,
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

/// Triangles per attribute chunk: the progress interval, so each chunk ends with a report.
constexpr std::size_t kChunkTriangles = kProgressInterval;

/// Triangles [first, last) of a mesh, `last` clamped to its triangle count.
struct TriangleRange {
    std::size_t first = 0;
    std::size_t last = std::numeric_limits<std::size_t>::max();
};

/// Inserts one feature per triangle of `range`. Attributes of chunk k + 1 are computed while
/// chunk k is inserted.
void writeTriangles(OGRLayer& layer, const TinMesh& mesh, const TinWriteOptions& options,
                    const ProgressTicker& ticker, const fs::path& output,
                    TriangleRange range = {}) {
    const auto columns = attributeColumns(options.attributes);
    std::vector<int> indices;
    for (const auto& column : columns)
        indices.push_back(fieldIndex(layer, column.name, output));

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

    for (const int index : indices)
        feature->SetField(index, 0.0);

    const std::size_t first = range.first;
    const std::size_t last = std::min(mesh.triangleCount(), range.last);
    const bool checkDbf = options.format == TinFormat::Shapefile;

    const std::size_t chunks =
        last > first ? (last - first + kChunkTriangles - 1) / kChunkTriangles : 0;
    const auto chunkRange = [&](std::size_t chunk) {
        const std::size_t begin = first + chunk * kChunkTriangles;
        return std::pair{begin, std::min(last, begin + kChunkTriangles)};
    };
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
            const Point3& a = mesh.vertices[mesh.triangles[3 * t]];
            const Point3& b = mesh.vertices[mesh.triangles[3 * t + 1]];
            const Point3& c = mesh.vertices[mesh.triangles[3 * t + 2]];
            ring->setPoint(0, a.x, a.y, a.z);
            ring->setPoint(1, b.x, b.y, b.z);
            ring->setPoint(2, c.x, c.y, c.z);
            ring->setPoint(3, a.x, a.y, a.z);

            if (!columns.empty()) {
                const TriangleAttributes& values = attributes[t - begin];
                for (std::size_t i = 0; i < columns.size(); ++i) {
                    const double value = values.*(columns[i].member);
                    if (checkDbf && !(std::fabs(value) < kDbfMaxMagnitude))
                        throwInvalid("triangle " + std::to_string(t) + " has " + columns[i].name +
                                     " = " + std::to_string(value) +
                                     ", which does not fit a Shapefile's DBF column; write a "
                                     "GeoPackage (.gpkg) instead of " +
                                     quoted(output));
                    // The raw field: SetField's type dispatch and set-marker bookkeeping cost
                    // more than the insert of a FlatGeobuf feature itself. Every field was
                    // set (to 0) before the loop, and a finite double never matches OGR's
                    // unset / null markers (NaN bit patterns).
                    feature->GetRawFieldRef(indices[i])->Real = value;
                }
            }
            // The driver numbers; a reused feature must be reset, or the next insert would
            // collide with the FID CreateFeature stored in it.
            feature->SetFID(OGRNullFID);
            createFeature(layer, *feature, "triangle", t, output);
        }
    };
    runBesideOneWriter<std::vector<TriangleAttributes>>(chunks, prepare, consume);
}

TinWriteResult writeFlatGeobuf(const TinMesh& mesh, const fs::path& output,
                               const TinWriteOptions& options,
                               std::optional<OGRSpatialReference>& srs,
                               const ProgressCallback& progress) {
    const double insertShare = options.spatialIndex ? 0.5 : kInsertShareWithoutIndex;
    const ProgressTicker ticker(kStage, progress, output, 0.0, insertShare, mesh.triangleCount());
    const AtomicOutput temporaries(kStage, output, existingTargetFor(options.overwrite),
                                   options.optionName);
    const fs::path temporary = temporaries.temporary(".fgb");

    // With an index: the triangles in the order GDAL will store them, and GDAL's temporary
    // copy of the features in memory when it fits (see the file comment).
    std::optional<TinMesh> indexOrdered;
    LayerSpec spec{output.stem().string(), wkbPolygon25D, TinFormat::FlatGeobuf};
    if (options.spatialIndex) {
        indexOrdered = reorderTriangles(mesh, packedRtreeOrder(mesh));
        const std::uint64_t temporaryBytes =
            mesh.triangleCount() *
            (kFgbFeatureBytes + kFgbColumnBytes * attributeColumns(options.attributes).size());
        const auto usableRam =
            static_cast<std::uint64_t>(std::max<GIntBig>(0, CPLGetUsablePhysicalRAM()));
        if (temporaryBytes <= usableRam / kFgbInMemoryRamDivisor)
            spec.temporaryDirectory = "/vsimem/";
    }
    const TinMesh& triangles = indexOrdered ? *indexOrdered : mesh;
    {
        // Closing the dataset, on every path, removes GDAL's temporary file, in /vsimem/ too.
        GDALDatasetUniquePtr dataset = createDataset("FlatGeobuf", temporary, output);
        OGRLayer* layer = createLayer(*dataset, spec, srs, options, output);
        for (const auto& column : attributeColumns(options.attributes))
            addField(*layer, column.name, OFTReal, TinFormat::FlatGeobuf, output);
        writeTriangles(*layer, triangles, options, ticker, output);
        ticker.report(mesh.triangleCount(),
                      options.spatialIndex ? "Building spatial index" : "Finishing FlatGeobuf");
        closeDataset(dataset, output);
    }
    // The last chance to cancel: GDAL builds the index while it closes the file, and a signal
    // that came meanwhile must still leave the old output in place.
    ticker.report(mesh.triangleCount(), "Finishing FlatGeobuf");
    temporaries.commit(temporary, output);
    return {mesh.triangleCount()};
}

/// Appends the last triangle of `mesh` to the Shapefile `shp`, in an update session whose DBF
/// writes the end-of-file mark after the record, as a single session would have.
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

TinWriteResult writeShapefile(const TinMesh& mesh, const fs::path& output,
                              const TinWriteOptions& options,
                              std::optional<OGRSpatialReference>& srs,
                              const ProgressCallback& progress) {
    const ProgressTicker ticker(kStage, progress, output, 0.0, kInsertShareWithoutIndex,
                                mesh.triangleCount());
    const AtomicOutput temporaries(kStage, output, existingTargetFor(options.overwrite),
                                   options.optionName);
    const fs::path temporaryDirectory = temporaries.temporary("");
    std::error_code error;
    if (!fs::create_directory(temporaryDirectory, error) || error)
        throwIo("cannot create the temporary directory " + quoted(temporaryDirectory) + ": " +
                (error ? error.message() : std::string("it exists")));

    // Lower-case names inside the temporary directory; shapefileComponent gives the final
    // names the case of the requested .shp.
    const std::string stem = output.stem().string();
    const fs::path temporaryShp = temporaryDirectory / (stem + ".shp");
    const std::size_t count = mesh.triangleCount();
    {
        // Every triangle but the last, without the DBF end-of-file mark (see the file comment).
        GDALDatasetUniquePtr dataset = createDataset("ESRI Shapefile", temporaryShp, output);
        OGRLayer* layer = createLayer(*dataset, {stem, wkbPolygon25D, TinFormat::Shapefile}, srs,
                                      options, output);
        for (const auto& column : attributeColumns(options.attributes))
            addField(*layer, column.name, OFTReal, TinFormat::Shapefile, output);
        writeTriangles(*layer, mesh, options, ticker, output, {0, count == 0 ? 0 : count - 1});
        closeDataset(dataset, output);
    }
    if (count > 0)
        appendLastTriangle(mesh, temporaryShp, options, ticker, output);
    ticker.report(count, "Finishing Shapefile");

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
                          [](const std::string& ext) { return lowercase(ext) != ".shp"; });
    std::vector<std::pair<fs::path, fs::path>> moves;
    for (const auto& ext : written)
        moves.emplace_back(temporaryDirectory / (stem + ext),
                           shapefileComponent(output, lowercase(ext)));
    // Without --overwrite a component that appeared meanwhile refuses the whole set.
    temporaries.commitAll(moves);

    // Stale sidecars of the replaced Shapefile go. Without --overwrite none existed at the
    // start (writeTin refused them), and one that appeared since is another program's.
    if (options.overwrite)
        for (const auto& sidecar : kShapefileSidecars)
            for (const auto& stale : shapefileComponentsAnyCase(output, sidecar)) {
                const bool rewritten =
                    std::any_of(moves.begin(), moves.end(),
                                [&](const auto& move) { return move.second == stale; });
                if (!rewritten)
                    fs::remove(stale, error);
            }
    return {mesh.triangleCount()};
}

} // namespace

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

std::vector<fs::path> ogrOutputFiles(const fs::path& output, TinFormat format) {
    std::vector<fs::path> files{output};
    if (format != TinFormat::Shapefile)
        return files;
    // Every component and sidecar, in both cases (issue 22, D1).
    const auto add = [&](const fs::path& file) {
        if (std::find(files.begin(), files.end(), file) == files.end())
            files.push_back(file);
    };
    for (const std::string_view ext : {".shp", ".shx", ".dbf"})
        for (const auto& file : shapefileComponentsAnyCase(output, ext))
            add(file);
    for (const auto& sidecar : kShapefileSidecars)
        for (const auto& file : shapefileComponentsAnyCase(output, sidecar))
            add(file);
    return files;
}

TinWriteResult writeOgrTin(const TinMesh& mesh, const fs::path& output,
                           const TinWriteOptions& options, const ProgressCallback& progress) {
    initialiseGdal();
    if (options.format == TinFormat::Shapefile && lowercase(output.extension().string()) != ".shp")
        throwInvalid("a Shapefile output must end in .shp, not " + quoted(output));
    std::optional<OGRSpatialReference> srs = parseOutputCrs(options.crsWkt);
    switch (options.format) {
    case TinFormat::GeoPackage:
        return writeGeoPackageTin(mesh, output, options, progress);
    case TinFormat::Shapefile:
        return writeShapefile(mesh, output, options, srs, progress);
    case TinFormat::FlatGeobuf:
        return writeFlatGeobuf(mesh, output, options, srs, progress);
    default:
        throwInvalid("not an OGR format");
    }
}

} // namespace terratin::io::detail

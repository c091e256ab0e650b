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

#include "../text.hpp"
#include "atomic_output.hpp"
#include "attribute_columns.hpp"
#include "gpkg/gpkg_tin_writer.hpp"
#include "ogr_dataset_support.hpp"
#include "ogr_triangle_layer.hpp"
#include "packed_rtree_order.hpp"
#include "terratin/error.hpp"
#include "terratin/gdal_error.hpp"
#include "writer_support.hpp"

#include <cpl_conv.h>
#include <gdal_priv.h>
#include <ogr_spatialref.h>
#include <ogrsf_frmts.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cstdint>
#include <optional>
#include <string_view>
#include <system_error>
#include <vector>

namespace terratin::io::detail {

using terratin::detail::lowercase;

namespace fs = std::filesystem;

namespace {

constexpr std::string_view kStage = kOgrStage;

/// Share of the writer's progress range given to inserting features; the rest is closing the
/// dataset (FlatGeobuf builds its index then) and the rename.
constexpr double kInsertShareWithoutIndex = 0.98;

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
/// grid's .prj).
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

TinWriteResult writeFlatGeobuf(const TinMesh& mesh, const fs::path& output,
                               const TinWriteOptions& options,
                               std::optional<OGRSpatialReference>& srs,
                               const ProgressCallback& progress) {
    const double insertShare = options.spatialIndex ? 0.5 : kInsertShareWithoutIndex;
    const ProgressTicker ticker(kStage, progress, output, 0.0, insertShare, mesh.triangleCount());
    const AtomicOutput temporaries(kStage, output, existingTargetFor(options.overwrite));
    const fs::path temporary = temporaries.temporary(".fgb");

    // With an index: the triangles in the order GDAL will store them, and GDAL's temporary
    // copy of the features in memory when it fits (see the file comment).
    std::optional<TinMesh> indexOrdered;
    TriangleLayerSpec spec{output.stem().string(), TinFormat::FlatGeobuf};
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
        OGRLayer& layer = createTriangleLayer(*dataset, spec, srs, options, output);
        writeTriangles(layer, triangles, options, ticker, output);
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

TinWriteResult writeShapefile(const TinMesh& mesh, const fs::path& output,
                              const TinWriteOptions& options,
                              std::optional<OGRSpatialReference>& srs,
                              const ProgressCallback& progress) {
    const ProgressTicker ticker(kStage, progress, output, 0.0, kInsertShareWithoutIndex,
                                mesh.triangleCount());
    const AtomicOutput temporaries(kStage, output, existingTargetFor(options.overwrite));
    const fs::path temporaryShp = makeShapefileDirectory(temporaries, output);
    const std::size_t count = mesh.triangleCount();
    {
        // Every triangle but the last, without the DBF end-of-file mark (see the file comment).
        GDALDatasetUniquePtr dataset = createDataset("ESRI Shapefile", temporaryShp, output);
        OGRLayer& layer = createTriangleLayer(
            *dataset, {output.stem().string(), TinFormat::Shapefile}, srs, options, output);
        writeTriangles(layer, mesh, options, ticker, output, {0, count == 0 ? 0 : count - 1});
        closeDataset(dataset, output);
    }
    if (count > 0)
        appendLastTriangle(mesh, temporaryShp, options, ticker, output);
    ticker.report(count, "Finishing Shapefile");
    commitShapefile(temporaries, temporaryShp, output, options.overwrite);
    return {mesh.triangleCount()};
}

} // namespace

fs::path makeShapefileDirectory(const AtomicOutput& temporaries, const fs::path& output) {
    const fs::path temporaryDirectory = temporaries.temporary("");
    std::error_code error;
    if (!fs::create_directory(temporaryDirectory, error) || error)
        throwIo("cannot create the temporary directory " + quoted(temporaryDirectory) + ": " +
                (error ? error.message() : std::string("it exists")));
    // Lower-case names inside the temporary directory; shapefileComponent gives the final
    // names the case of the requested .shp.
    return temporaryDirectory / (output.stem().string() + ".shp");
}

void commitShapefile(const AtomicOutput& temporaries, const fs::path& temporaryShp,
                     const fs::path& output, bool overwrite) {
    // Every file GDAL wrote, by its extension after the stem (".shp", ".shx", ".dbf", ".prj",
    // ".cpg").
    const fs::path temporaryDirectory = temporaryShp.parent_path();
    const std::string stem = temporaryShp.stem().string();
    std::vector<std::string> written;
    std::error_code error;
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
    // start (the writer refused them), and one that appeared since is another program's.
    if (overwrite)
        for (const auto& sidecar : kShapefileSidecars)
            for (const auto& stale : shapefileComponentsAnyCase(output, sidecar)) {
                const bool rewritten =
                    std::any_of(moves.begin(), moves.end(),
                                [&](const auto& move) { return move.second == stale; });
                if (!rewritten)
                    fs::remove(stale, error);
            }
}

void checkShapefileName(const fs::path& output) {
    if (lowercase(output.extension().string()) != ".shp")
        throwInvalid("a Shapefile output must end in .shp, not " + quoted(output));
}

std::vector<fs::path> ogrOutputFiles(const fs::path& output, TinFormat format) {
    std::vector<fs::path> files{output};
    if (format != TinFormat::Shapefile)
        return files;
    // Every component and sidecar, in both cases: any of them present means the output exists,
    // even one that belongs to another data set of the same name.
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
    if (options.format == TinFormat::Shapefile)
        checkShapefileName(output);
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

#include "gpkg_append.hpp"

#include "../atomic_output.hpp"
#include "../ogr_dataset_support.hpp"
#include "gpkg_layer_catalog.hpp"
#include "gpkg_tin_writer.hpp"
#include "terratin/error.hpp"

#include <fstream>
#include <string>
#include <string_view>

namespace terratin::io::detail {

namespace fs = std::filesystem;

namespace {

/// The schema name of the scratch GeoPackage while it is attached.
constexpr const char* kScratchSchema = "terratin_scratch";

std::string cannotAddTo(const fs::path& output) {
    return std::string(kOgrStage) + ": cannot add layers to " + quoted(output);
}

/// A file that is neither empty nor starts as every SQLite database does ("SQLite format 3"
/// and a NUL, the header's first 16 bytes): refused before SQLite opens it.
void refuseNonSqliteFile(const fs::path& output) {
    constexpr std::string_view kSqliteMagic("SQLite format 3\0", 16);
    std::ifstream file(output, std::ios::binary);
    std::string header(kSqliteMagic.size(), '\0');
    file.read(header.data(), static_cast<std::streamsize>(header.size()));
    const auto got = static_cast<std::size_t>(file.gcount());
    if (got > 0 && std::string_view(header.data(), got) != kSqliteMagic.substr(0, got))
        throw InvalidInputError(cannotAddTo(output) +
                                ": it is not a GeoPackage (not an SQLite database)");
}

void refuseReadOnly(const SqliteConnection& db, const fs::path& output) {
    if (db.isReadOnly())
        throw IoError(cannotAddTo(output) +
                      ": it is read-only for this user (the file or its directory is not "
                      "writable)");
}

/// SQLite's quick_check: page structure, free list, record formats and NOT NULL constraints;
/// not the contents of indexes, which would read every index in full.
void refuseDamagedFile(SqliteConnection& db, const fs::path& output) {
    SqliteStatement check(db, "PRAGMA main.quick_check(1)");
    const std::string verdict = check.nextRow() ? check.textColumn(0) : "no answer";
    if (verdict != "ok")
        throw InvalidInputError(cannotAddTo(output) + ": SQLite's quick_check fails on it (" +
                                verdict + "); repair or replace it first");
}

/// Removes layer `name` when options.overwrite allows; refuses a layer without it, and a
/// table of the same name that is no layer in any case.
void makeRoomForLayer(SqliteConnection& db, const std::string& name, const TinWriteOptions& options,
                      const fs::path& output) {
    if (hasLayer(db, name)) {
        if (!options.overwrite)
            throw InvalidInputError(std::string(kOgrStage) + ": the GeoPackage " + quoted(output) +
                                    " already has a layer '" + name + "'; choose another " +
                                    markOption("layer") + " or use " + markOption("overwrite") +
                                    " to replace it");
        dropLayer(db, name, output);
    }
    if (hasSchemaObject(db, name))
        throw InvalidInputError(std::string(kOgrStage) + ": the GeoPackage " + quoted(output) +
                                " has a table '" + name + "' that is not a layer; choose another " +
                                markOption("layer"));
}

} // namespace

TinWriteResult appendGeoPackageTin(const TinMesh& mesh, const fs::path& output,
                                   const TinWriteOptions& options,
                                   const std::vector<GpkgLayerJob>& jobs,
                                   const ProgressTicker& ticker) {
    // The scratch file is this run's own, and removed on every way out (after the
    // connection, which is closed first).
    const AtomicOutput scratchFiles(kOgrStage, output, ExistingTarget::Refuse);
    const fs::path scratch = scratchFiles.temporary(".gpkg");
    refuseNonSqliteFile(output);
    SqliteConnection db(kOgrStage, output, output);
    refuseReadOnly(db, output);
    createGpkgTinLayers(scratch, 0, gpkgLayerNames(options), options, output);

    db.waitForLocks(options.lockWaitSeconds, [&] {
        ticker.report(0, "Waiting for another program's lock on the GeoPackage");
    });
    db.execute("PRAGMA main.cache_size = -" + std::to_string(kGpkgPageCacheKiB));
    db.execute("ATTACH DATABASE " + quoteLiteral(scratch.string()) + " AS " + kScratchSchema);
    // IMMEDIATE takes the write lock now: no other writer can slip in between the checks and
    // the writes, and no upgrade from a read lock can deadlock with another writer's.
    db.execute("BEGIN IMMEDIATE");
    requireGeoPackage(db, output);
    refuseDamagedFile(db, output);
    for (const GpkgLayerJob& job : jobs)
        makeRoomForLayer(db, job.name, options, output);
    for (const GpkgLayerJob& job : jobs)
        copyLayerDefinition(db, kScratchSchema, job.name);

    TinWriteResult result = fillGpkgLayers(db, mesh, jobs, options.spatialIndex, ticker);
    // The last chance to cancel: until COMMIT the file is as it was.
    ticker.reportDone("Finishing GeoPackage");
    db.execute("COMMIT");
    db.execute(std::string("DETACH DATABASE ") + kScratchSchema);
    db.close();
    return result;
}

} // namespace terratin::io::detail

// Layers added to a user's GeoPackage go in through SQLite's own locks and journal: what other
// programs wrote (committed rows still in a WAL, a live writer's rows, an open exclusive
// transaction, a crashed writer's hot journal) is never lost, concurrent appends both land,
// and a file that is damaged, read-only or no GeoPackage is refused before it is touched.

#include "terratin/io/tin_writer.hpp"

#include "mesh_readers.hpp"
#include "ogr_test_support.hpp"
#include "sqlite_query.hpp"
#include "temporary_directory.hpp"
#include "terratin/error.hpp"
#include "terratin/gdal_error.hpp"

#include <gdal_priv.h>
#include <ogrsf_frmts.h>
#include <sqlite3.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <fstream>
#include <iterator>
#include <string>
#include <string_view>
#include <thread>
#include <vector>

namespace terratin::io {
namespace {

using test::rtreeCheck;
using test::sqliteText;
using test::TemporaryDirectory;

TinWriteOptions appendOptions(const std::string& layer) {
    TinWriteOptions options;
    options.format = TinFormat::GeoPackage;
    options.crsWkt = test::utm10nWkt();
    options.appendLayer = true;
    options.layerName = layer;
    return options;
}

/// A GeoPackage with a TIN layer "tin" and a table "notes" holding one row, "first".
std::filesystem::path userGeoPackage(const TemporaryDirectory& directory,
                                     const char* journalMode = "delete") {
    const auto path = directory / "user.gpkg";
    TinWriteOptions options = appendOptions("tin");
    options.appendLayer = false;
    writeTin(test::gridTin(6), path, options);
    sqlite3* db = nullptr;
    EXPECT_EQ(sqlite3_open(path.c_str(), &db), SQLITE_OK);
    const std::string sql = std::string("PRAGMA journal_mode = ") + journalMode +
                            "; CREATE TABLE notes (text TEXT); INSERT INTO notes VALUES ('first');";
    EXPECT_EQ(sqlite3_exec(db, sql.c_str(), nullptr, nullptr, nullptr), SQLITE_OK);
    sqlite3_close(db);
    return path;
}

std::string notes(const std::filesystem::path& path) {
    return sqliteText(path, "SELECT group_concat(text, ',') FROM (SELECT text FROM notes "
                            "ORDER BY rowid)");
}

int execute(sqlite3* db, const std::string& sql) {
    return sqlite3_exec(db, sql.c_str(), nullptr, nullptr, nullptr);
}

std::string fileBytes(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

/// Runs `work` in a child process that ends with _exit, as a killed writer does: SQLite gets
/// no chance to checkpoint its WAL or remove its journal.
template <class Work> void inKilledChild(Work&& work) {
    const pid_t child = fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
        work();
        _exit(0);
    }
    int status = 0;
    ASSERT_EQ(waitpid(child, &status, 0), child);
    ASSERT_TRUE(WIFEXITED(status));
}

/// The message of the InvalidInputError an append to `path` is refused with; a test failure
/// when it is not refused.
std::string appendRefusal(const std::filesystem::path& path) {
    try {
        writeTin(test::gridTin(4), path, appendOptions("second"));
    } catch (const InvalidInputError& error) {
        return error.what();
    }
    ADD_FAILURE() << "the append to " << path << " was not refused";
    return {};
}

/// What the directory holds besides `keep`.
std::vector<std::string> otherEntries(const TemporaryDirectory& directory,
                                      const std::filesystem::path& keep) {
    std::vector<std::string> names;
    for (const auto& entry : std::filesystem::directory_iterator(directory.path()))
        if (entry.path() != keep)
            names.push_back(entry.path().filename().string());
    return names;
}

TEST(GeoPackageAppend, KeepsACommitStillInTheWal_OfAWriterThatWasKilled) {
    TemporaryDirectory directory;
    const auto path = userGeoPackage(directory, "wal");
    inKilledChild([&] {
        sqlite3* db = nullptr;
        sqlite3_open(path.c_str(), &db);
        execute(db, "INSERT INTO notes VALUES ('in the wal')");
    });
    ASSERT_TRUE(std::filesystem::exists(path.string() + "-wal"));
    writeTin(test::gridTin(4), path, appendOptions("second"));
    EXPECT_EQ(notes(path), "first,in the wal");
    EXPECT_EQ(sqliteText(path, "SELECT count(*) FROM second"), std::to_string(2 * 3 * 3));
    EXPECT_EQ(sqliteText(path, "PRAGMA integrity_check"), "ok");
    EXPECT_EQ(rtreeCheck(path, "second"), "ok");
}

TEST(GeoPackageAppend, KeepsALiveWalWritersRows_AndHoldsItOffWhileWriting) {
    TemporaryDirectory directory;
    const auto path = userGeoPackage(directory, "wal");
    sqlite3* other = nullptr;
    ASSERT_EQ(sqlite3_open(path.c_str(), &other), SQLITE_OK);
    ASSERT_EQ(execute(other, "INSERT INTO notes VALUES ('before')"), SQLITE_OK);
    int refusedDuring = 0;
    const ProgressCallback tryWritingMeanwhile = [&](double, std::string_view message) {
        if (message == "Writing triangles" &&
            execute(other, "INSERT INTO notes VALUES ('during')") == SQLITE_BUSY)
            ++refusedDuring;
        return true;
    };
    writeTin(test::gridTin(5), path, appendOptions("second"), tryWritingMeanwhile);
    EXPECT_GT(refusedDuring, 0) << "the append held no write lock while it wrote";
    ASSERT_EQ(execute(other, "INSERT INTO notes VALUES ('after')"), SQLITE_OK);
    sqlite3_close(other);
    EXPECT_EQ(notes(path), "first,before,after");
    EXPECT_EQ(sqliteText(path, "SELECT count(*) FROM second"), std::to_string(2 * 4 * 4));
    EXPECT_EQ(sqliteText(path, "PRAGMA integrity_check"), "ok");
}

TEST(GeoPackageAppend, WaitsForAnotherConnectionsExclusiveTransaction_AndKeepsItsRow) {
    TemporaryDirectory directory;
    const auto path = userGeoPackage(directory);
    sqlite3* other = nullptr;
    ASSERT_EQ(sqlite3_open(path.c_str(), &other), SQLITE_OK);
    ASSERT_EQ(execute(other, "BEGIN EXCLUSIVE; INSERT INTO notes VALUES ('pending')"), SQLITE_OK);
    std::atomic<int> commitStatus{-1};
    std::thread committer([&] {
        std::this_thread::sleep_for(std::chrono::milliseconds(300));
        commitStatus = execute(other, "COMMIT");
    });
    writeTin(test::gridTin(4), path, appendOptions("second"));
    committer.join();
    sqlite3_close(other);
    EXPECT_EQ(commitStatus.load(), SQLITE_OK);
    EXPECT_EQ(notes(path), "first,pending");
    EXPECT_EQ(sqliteText(path, "SELECT count(*) FROM second"), std::to_string(2 * 3 * 3));
}

TEST(GeoPackageAppend, GivesUpOnALockHeldTooLong_AndTheOtherCommitStillWorks) {
    TemporaryDirectory directory;
    const auto path = userGeoPackage(directory);
    sqlite3* other = nullptr;
    ASSERT_EQ(sqlite3_open(path.c_str(), &other), SQLITE_OK);
    ASSERT_EQ(execute(other, "BEGIN EXCLUSIVE; INSERT INTO notes VALUES ('pending')"), SQLITE_OK);
    TinWriteOptions options = appendOptions("second");
    options.lockWaitSeconds = 0.2;
    try {
        writeTin(test::gridTin(4), path, options);
        ADD_FAILURE() << "the append did not wait for the lock";
    } catch (const IoError& error) {
        EXPECT_NE(std::string(error.what()).find("another program holds a lock on it"),
                  std::string::npos)
            << error.what();
    }
    EXPECT_EQ(execute(other, "COMMIT"), SQLITE_OK);
    sqlite3_close(other);
    EXPECT_EQ(notes(path), "first,pending");
    EXPECT_EQ(sqliteText(path, "SELECT count(*) FROM gpkg_contents WHERE table_name = 'second'"),
              "0");
    EXPECT_TRUE(otherEntries(directory, path).empty());
}

TEST(GeoPackageAppend, ACancelWhileWaitingForALock_EndsTheWaitAtOnce) {
    TemporaryDirectory directory;
    const auto path = userGeoPackage(directory);
    sqlite3* other = nullptr;
    ASSERT_EQ(sqlite3_open(path.c_str(), &other), SQLITE_OK);
    ASSERT_EQ(execute(other, "BEGIN EXCLUSIVE; INSERT INTO notes VALUES ('pending')"), SQLITE_OK);
    int waits = 0;
    const ProgressCallback cancelAfterAFewWaits = [&](double, std::string_view message) {
        return message.find("Waiting") == std::string_view::npos || ++waits < 4;
    };
    const auto start = std::chrono::steady_clock::now();
    EXPECT_THROW(writeTin(test::gridTin(4), path, appendOptions("second"), cancelAfterAFewWaits),
                 Cancelled);
    // The default wait is 30 s; the cancel came at the fourth poll.
    EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(10));
    EXPECT_EQ(waits, 4);
    EXPECT_EQ(execute(other, "COMMIT"), SQLITE_OK);
    sqlite3_close(other);
    EXPECT_EQ(notes(path), "first,pending");
}

TEST(GeoPackageAppend, RollsBackACrashedWritersHotJournal_BeforeAppending) {
    TemporaryDirectory directory;
    const auto path = userGeoPackage(directory);
    inKilledChild([&] {
        sqlite3* db = nullptr;
        sqlite3_open(path.c_str(), &db);
        // A small page cache spills the uncommitted rows into the file itself, with the
        // journal that undoes them.
        execute(db, "PRAGMA cache_size = 2; BEGIN; WITH RECURSIVE n(i) AS (SELECT 1 UNION ALL "
                    "SELECT i + 1 FROM n WHERE i < 20000) INSERT INTO notes SELECT "
                    "'uncommitted ' || hex(randomblob(50)) FROM n");
    });
    ASSERT_TRUE(std::filesystem::exists(path.string() + "-journal"));
    ASSERT_GT(std::filesystem::file_size(path.string() + "-journal"), 0u);
    writeTin(test::gridTin(4), path, appendOptions("second"));
    EXPECT_EQ(notes(path), "first");
    EXPECT_EQ(sqliteText(path, "PRAGMA integrity_check"), "ok");
    EXPECT_EQ(sqliteText(path, "SELECT count(*) FROM second"), std::to_string(2 * 3 * 3));
}

TEST(GeoPackageAppend, TwoAppendsAtOnce_BothLayersArrive) {
    TemporaryDirectory directory;
    const auto path = userGeoPackage(directory);
    std::vector<std::thread> appends;
    std::atomic<int> failures{0};
    for (const char* layer : {"left", "right"})
        appends.emplace_back([&, layer] {
            try {
                writeTin(test::gridTin(60), path, appendOptions(layer));
            } catch (const std::exception&) {
                ++failures;
            }
        });
    for (auto& append : appends)
        append.join();
    EXPECT_EQ(failures.load(), 0);
    for (const char* layer : {"left", "right"}) {
        EXPECT_EQ(sqliteText(path, std::string("SELECT count(*) FROM ") + layer),
                  std::to_string(2 * 59 * 59));
        EXPECT_EQ(rtreeCheck(path, layer), "ok");
    }
    EXPECT_EQ(notes(path), "first");
    EXPECT_EQ(sqliteText(path, "PRAGMA integrity_check"), "ok");
}

TEST(GeoPackageAppend, ChangesTheFileInPlace_KeepingItsInodeAndLeavingNothingBeside) {
    TemporaryDirectory directory;
    const auto path = userGeoPackage(directory);
    struct stat before {};
    ASSERT_EQ(stat(path.c_str(), &before), 0);
    writeTin(test::gridTin(4), path, appendOptions("second"));
    struct stat after {};
    ASSERT_EQ(stat(path.c_str(), &after), 0);
    EXPECT_EQ(after.st_ino, before.st_ino);
    EXPECT_EQ(after.st_uid, before.st_uid);
    EXPECT_EQ(after.st_mode, before.st_mode);
    EXPECT_TRUE(otherEntries(directory, path).empty());
}

TEST(GeoPackageAppend, ACancelWhileWritingRows_LeavesTheFileByteForByteAsItWas) {
    TemporaryDirectory directory;
    const auto path = userGeoPackage(directory);
    const std::string original = fileBytes(path);
    const ProgressCallback cancelInTheRows = [](double, std::string_view message) {
        return message != "Writing triangles";
    };
    EXPECT_THROW(writeTin(test::gridTin(40), path, appendOptions("second"), cancelInTheRows),
                 Cancelled);
    EXPECT_EQ(fileBytes(path), original);
    EXPECT_TRUE(otherEntries(directory, path).empty());
}

TEST(GeoPackageAppend, WritesRtreeNodesSqliteAccepts_OnAFileOf512BytePages) {
    TemporaryDirectory directory;
    const auto path = userGeoPackage(directory);
    {
        sqlite3* db = nullptr;
        ASSERT_EQ(sqlite3_open(path.c_str(), &db), SQLITE_OK);
        ASSERT_EQ(execute(db, "PRAGMA page_size = 512; VACUUM"), SQLITE_OK);
        sqlite3_close(db);
    }
    ASSERT_EQ(sqliteText(path, "PRAGMA page_size"), "512");
    writeTin(test::gridTin(30), path, appendOptions("second"));
    EXPECT_EQ(rtreeCheck(path, "second"), "ok");
    initialiseGdal();
    GDALDatasetUniquePtr dataset(GDALDataset::Open(path.c_str(), GDAL_OF_VECTOR));
    ASSERT_TRUE(dataset);
    OGRLayer& layer = *dataset->GetLayerByName("second");
    ASSERT_TRUE(layer.TestCapability(OLCFastSpatialFilter));
    // gridTin(30) has cells of 10 m from (500000, 5000000); the filter holds about a quarter.
    layer.SetSpatialFilterRect(500005.0, 5000005.0, 500145.0, 5000145.0);
    EXPECT_GE(layer.GetFeatureCount(), 2 * 13 * 13);
    EXPECT_LT(layer.GetFeatureCount(), 2 * 29 * 29);
}

TEST(GeoPackageAppend, RefusesAFileThatFailsSqlitesQuickCheck_AndLeavesItAsItWas) {
    TemporaryDirectory directory;
    const auto path = userGeoPackage(directory);
    {
        // Bytes 36-39 of the header count the free-list pages: a count the list does not have.
        std::fstream file(path, std::ios::in | std::ios::out | std::ios::binary);
        file.seekp(36);
        const char count[4] = {0, 0, 0, 5};
        file.write(count, 4);
    }
    ASSERT_NE(sqliteText(path, "PRAGMA quick_check"), "ok");
    const std::string damaged = fileBytes(path);
    const std::string refusal = appendRefusal(path);
    EXPECT_NE(refusal.find("quick_check fails"), std::string::npos) << refusal;
    EXPECT_EQ(fileBytes(path), damaged);
}

TEST(GeoPackageAppend, RefusesAnSqliteFileThatIsNoGeoPackage) {
    TemporaryDirectory directory;
    const auto path = directory / "plain.gpkg";
    sqlite3* db = nullptr;
    ASSERT_EQ(sqlite3_open(path.c_str(), &db), SQLITE_OK);
    ASSERT_EQ(execute(db, "CREATE TABLE t (x)"), SQLITE_OK);
    sqlite3_close(db);
    const std::string original = fileBytes(path);
    const std::string refusal = appendRefusal(path);
    EXPECT_NE(refusal.find("it is not a GeoPackage"), std::string::npos) << refusal;
    EXPECT_EQ(fileBytes(path), original);
}

TEST(GeoPackageAppend, OverwriteReplacesTheLayerWholly_AndTheCrsRowIsShared) {
    TemporaryDirectory directory;
    const auto path = userGeoPackage(directory);
    TinWriteOptions options = appendOptions("second");
    options.nodes = true;
    options.edges = true;
    writeTin(test::gridTin(8), path, options);
    options.overwrite = true;
    writeTin(test::gridTin(5), path, options);
    EXPECT_EQ(sqliteText(path, "SELECT count(*) FROM second"), std::to_string(2 * 4 * 4));
    EXPECT_EQ(sqliteText(path, "SELECT count(*) FROM second_nodes"), "25");
    for (const char* catalogue : {"gpkg_contents", "gpkg_geometry_columns", "gpkg_ogr_contents"})
        EXPECT_EQ(sqliteText(path, std::string("SELECT count(*) FROM ") + catalogue +
                                       " WHERE table_name LIKE 'second%'"),
                  "3")
            << catalogue;
    EXPECT_EQ(sqliteText(path, "SELECT feature_count FROM gpkg_ogr_contents WHERE table_name = "
                               "'second'"),
              std::to_string(2 * 4 * 4));
    EXPECT_EQ(sqliteText(path, "SELECT count(*) FROM sqlite_master WHERE name LIKE "
                               "'rtree_second%' AND type = 'table' AND sql LIKE '%VIRTUAL%'"),
              "3");
    EXPECT_EQ(sqliteText(path, "SELECT count(*) FROM gpkg_spatial_ref_sys WHERE "
                               "organization_coordsys_id = 26910"),
              "1");
    EXPECT_EQ(sqliteText(path, "SELECT count(DISTINCT srs_id) FROM gpkg_geometry_columns"), "1");
    for (const char* layer : {"tin", "second", "second_nodes", "second_edges"})
        EXPECT_EQ(rtreeCheck(path, layer), "ok") << layer;
    initialiseGdal();
    GDALDatasetUniquePtr dataset(GDALDataset::Open(path.c_str(), GDAL_OF_VECTOR));
    ASSERT_TRUE(dataset);
    EXPECT_EQ(dataset->GetLayerByName("second")->GetFeatureCount(), 2 * 4 * 4);
    EXPECT_EQ(dataset->GetLayerByName("tin")->GetFeatureCount(), 2 * 5 * 5);
}

TEST(GeoPackageAppend, ALayerInAnotherCrs_GetsItsOwnCrsRow) {
    TemporaryDirectory directory;
    const auto path = userGeoPackage(directory);
    TinWriteOptions options = appendOptions("mercator");
    OGRSpatialReference srs;
    ASSERT_EQ(srs.importFromEPSG(3857), OGRERR_NONE);
    char* wkt = nullptr;
    ASSERT_EQ(srs.exportToWkt(&wkt), OGRERR_NONE);
    options.crsWkt = wkt;
    CPLFree(wkt);
    writeTin(test::gridTin(4), path, options);
    EXPECT_EQ(sqliteText(path, "SELECT organization || ':' || organization_coordsys_id FROM "
                               "gpkg_spatial_ref_sys s JOIN gpkg_geometry_columns g ON "
                               "g.srs_id = s.srs_id WHERE g.table_name = 'mercator'"),
              "EPSG:3857");
    initialiseGdal();
    GDALDatasetUniquePtr dataset(GDALDataset::Open(path.c_str(), GDAL_OF_VECTOR));
    ASSERT_TRUE(dataset);
    const OGRSpatialReference* read = dataset->GetLayerByName("mercator")->GetSpatialRef();
    ASSERT_NE(read, nullptr);
    EXPECT_STREQ(read->GetAuthorityCode(nullptr), "3857");
}

} // namespace
} // namespace terratin::io

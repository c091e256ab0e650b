// Tests of LAZ through the LAS reader: each LAZ with an uncompressed twin gives exactly the
// twin's points, CRS and counts under every filter and on any number of threads; chunks decode
// on several threads in file order, the first failing chunk in file order is the one reported,
// and cancellation stops the read. The files are read in place from TERRATIN_SHARED_DEMS; a
// test skips itself when they are absent.

#include "laz_file.hpp"
#include "laz_point_runs.hpp"
#include "laz_test_files.hpp"
#include "terratin/error.hpp"
#include "terratin/io/las_reader.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <mutex>
#include <set>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

namespace terratin::io {
namespace {

using laz::test::sharedDem;
using laz::test::sharedLaz;

struct Twin {
    const char* laz;
    const char* las; ///< relative to the shared DEM folder
};

void PrintTo(const Twin& twin, std::ostream* out) {
    *out << twin.laz;
}

const std::vector<Twin> kTwins{
    {"lazrs__point-time-color.laz", "laz/lazrs__point-time-color.las"},
    {"lazrs__extra-bytes.laz", "laz/lazrs__extra-bytes.las"},
    {"pdal__simple-laszip-compressor-version-1.2r0.laz", "laz/laspy__simple.las"},
    {"pdal__autzen_trim.laz", "pdal__autzen_trim.las"},
    {"lidr__Megaplot.laz", "laz/lasr__Megaplot.las"},
    {"lidr__Topography.laz", "laz/lasr__Topography.las"},
    {"lidr__MixedConifer.laz", "laz/lasr__MixedConifer.las"},
    {"rlas__example.laz", "laz/rlas__example.las"},
    {"lazperf__no-points-1.3.laz", "laz/lazperf__no-points-1.3.las"},
    {"laspy__1_4_w_evlr.laz", "laz/laspy__1_4_w_evlr.las"}, // layered, EVLRs after the table
};

bool present(const Twin& twin) {
    return std::filesystem::exists(sharedLaz(twin.laz)) &&
           std::filesystem::exists(sharedDem(twin.las));
}

LasReadOptions optionsWith(std::vector<int> classes, LasReturns returns, unsigned threads) {
    LasReadOptions options;
    options.classes = std::move(classes);
    options.returns = returns;
    options.threads = threads;
    return options;
}

void expectSameCloud(const PointCloud& laz, const PointCloud& las, const std::string& what) {
    EXPECT_EQ(laz.recordsRead, las.recordsRead) << what;
    EXPECT_EQ(laz.filteredOut, las.filteredOut) << what;
    EXPECT_EQ(laz.crsWkt, las.crsWkt) << what;
    ASSERT_EQ(laz.points.size(), las.points.size()) << what;
    for (std::size_t i = 0; i < laz.points.size(); ++i) {
        const Point3& a = laz.points[i];
        const Point3& b = las.points[i];
        ASSERT_TRUE(a.x == b.x && a.y == b.y && a.z == b.z) << what << ": point " << i;
    }
}

class LazTwinReadTest : public ::testing::TestWithParam<Twin> {};

TEST_P(LazTwinReadTest, GivesTheTwinsPoints_UnderEveryFilterAndThreadCount) {
    const Twin twin = GetParam();
    if (!present(twin))
        GTEST_SKIP() << "shared LAZ test files absent";
    const std::vector<LasReadOptions> filters{
        optionsWith({}, LasReturns::All, 1),   optionsWith({2}, LasReturns::All, 2),
        optionsWith({}, LasReturns::First, 3), optionsWith({1, 2}, LasReturns::Last, 2),
        optionsWith({}, LasReturns::All, 0),
    };
    for (std::size_t f = 0; f < filters.size(); ++f) {
        const PointCloud laz = readLasPoints(sharedLaz(twin.laz).string(), filters[f]);
        const PointCloud las = readLasPoints(sharedDem(twin.las).string(), filters[f]);
        expectSameCloud(laz, las, std::string(twin.laz) + ", filter " + std::to_string(f));
    }
}

INSTANTIATE_TEST_SUITE_P(SharedFiles, LazTwinReadTest, ::testing::ValuesIn(kTwins));

// A file of many chunks (11) gives the same points in the same order on 1 to 5 threads.
TEST(LazParallel, GivesTheSamePointsInFileOrder_OnAnyNumberOfThreads) {
    const auto path = sharedLaz("pdal__lone-star.laz");
    if (!std::filesystem::exists(path))
        GTEST_SKIP() << "shared LAZ test files absent";
    const PointCloud one = readLasPoints(path.string(), optionsWith({}, LasReturns::All, 1));
    EXPECT_EQ(one.points.size(), 518862U);
    for (const unsigned threads : {2U, 3U, 5U}) {
        const PointCloud many =
            readLasPoints(path.string(), optionsWith({}, LasReturns::All, threads));
        expectSameCloud(many, one, std::to_string(threads) + " threads");
    }
}

// Every chunk is decoded exactly once and taken in order, in rounds, whatever the threads.
TEST(LazParallel, TakesEveryChunkOnceInOrder) {
    const auto path = sharedLaz("pdal__lone-star.laz");
    if (!std::filesystem::exists(path))
        GTEST_SKIP() << "shared LAZ test files absent";
    const laz::LazFile file = laz::LazFile::open(path.string());
    for (const unsigned threads : {1U, 2U, 4U}) {
        std::mutex mutex;
        std::vector<std::uint64_t> decoded(file.chunks().size(), 0);
        std::vector<std::size_t> taken;
        laz::ChunkRunOptions options;
        options.threads = threads;
        options.recordsPerPiece = 1000; // several pieces per chunk
        const bool finished = laz::decodeChunksInOrder(
            file, options,
            [&](std::size_t chunk, std::span<const std::byte> records) {
                const std::lock_guard lock(mutex);
                decoded[chunk] += records.size() / file.header().recordLength;
            },
            [&](std::size_t chunk) {
                taken.push_back(chunk);
                return true;
            });
        EXPECT_TRUE(finished);
        ASSERT_EQ(taken.size(), file.chunks().size());
        for (std::size_t i = 0; i < taken.size(); ++i) {
            EXPECT_EQ(taken[i], i);
            EXPECT_EQ(decoded[i], file.chunks()[i].pointCount) << "chunk " << i;
        }
    }
}

// Two chunks fail; the one reported is the first in file order, on any number of threads.
TEST(LazParallel, ReportsTheFirstFailingChunkInFileOrder) {
    const auto path = sharedLaz("pdal__lone-star.laz");
    if (!std::filesystem::exists(path))
        GTEST_SKIP() << "shared LAZ test files absent";
    const laz::LazFile file = laz::LazFile::open(path.string());
    for (const unsigned threads : {1U, 2U, 4U}) {
        laz::ChunkRunOptions options;
        options.threads = threads;
        std::vector<std::size_t> taken;
        try {
            (void)laz::decodeChunksInOrder(
                file, options,
                [&](std::size_t chunk, std::span<const std::byte>) {
                    if (chunk == 2 || chunk == 3)
                        throw std::runtime_error("chunk " + std::to_string(chunk));
                },
                [&](std::size_t chunk) {
                    taken.push_back(chunk);
                    return true;
                });
            FAIL() << "no error on " << threads << " threads";
        } catch (const std::runtime_error& error) {
            EXPECT_EQ(std::string(error.what()), "chunk 2") << threads << " threads";
        }
        EXPECT_EQ(taken, (std::vector<std::size_t>{0, 1})) << threads << " threads";
    }
}

TEST(LazParallel, StopsWhenProgressCancels) {
    const auto path = sharedLaz("pdal__lone-star.laz");
    if (!std::filesystem::exists(path))
        GTEST_SKIP() << "shared LAZ test files absent";
    int calls = 0;
    const ProgressCallback cancelAtOnce = [&](double fraction, std::string_view phase) {
        ++calls;
        EXPECT_GT(fraction, 0.0);
        EXPECT_EQ(phase, "reading LAZ");
        return false;
    };
    EXPECT_THROW(readLasPoints(path.string(), optionsWith({}, LasReturns::All, 2), cancelAtOnce),
                 Cancelled);
    EXPECT_EQ(calls, 1);
}

// Every shared LAZ file reads, every record counted (kept or filtered out), as many as its
// header says; the broken ones are the next test's.
TEST(LazReading, ReadsEverySharedFile_AsManyRecordsAsItsHeaderSays) {
    const auto folder = sharedLaz("");
    if (!std::filesystem::exists(folder))
        GTEST_SKIP() << "shared LAZ test files absent";
    std::size_t files = 0;
    for (const auto& entry : std::filesystem::directory_iterator(folder)) {
        const std::string name = entry.path().filename().string();
        if (entry.path().extension() != ".laz" || name.find("broken") != std::string::npos)
            continue;
        const LasHeader header = readLasHeader(entry.path().string());
        EXPECT_TRUE(header.compressed) << name;
        const PointCloud cloud =
            readLasPoints(entry.path().string(), optionsWith({2}, LasReturns::First, 2));
        EXPECT_EQ(cloud.kind, InputKind::Laz) << name;
        EXPECT_EQ(cloud.recordsRead, header.pointCount) << name;
        EXPECT_EQ(cloud.points.size() + cloud.filteredOut, header.pointCount) << name;
        ++files;
    }
    EXPECT_GE(files, 30U);
}

// The broken files of LASzip's own tests: one line naming the file and what is wrong.
TEST(LazReading, ReportsEachBrokenFile_InOneLine) {
    const std::vector<std::pair<const char*, const char*>> broken{
        {"laszip__broken_coder.laz", "coder 15"},
        {"laszip__broken_compressor.laz", "compressor 16"},
        {"laszip__broken_type.laz", "type 22"},
        {"laszip__broken_version.laz", "version 6"},
    };
    for (const auto& [name, fault] : broken) {
        const auto path = sharedLaz(name);
        if (!std::filesystem::exists(path))
            GTEST_SKIP() << "shared LAZ test files absent";
        try {
            (void)readLasPoints(path.string());
            ADD_FAILURE() << name << " was read";
        } catch (const InvalidInputError& error) {
            const std::string message = error.what();
            EXPECT_NE(message.find(name), std::string::npos) << message;
            EXPECT_NE(message.find(fault), std::string::npos) << message;
            EXPECT_EQ(message.find('\n'), std::string::npos) << message;
        }
    }
}

} // namespace
} // namespace terratin::io

// TileHandout (--memory-limit over MPI ranks): tiles go out in order; those back
// before their turn are counted until their turn comes, and no tile goes out while they hold
// more than the bound; a pause always ends, since the tile in turn is always out in work.

#include "terratin/error.hpp"
#include "terratin/tile/tile_handout.hpp"

#include <gtest/gtest.h>

#include <algorithm>

#include <cstdint>
#include <optional>
#include <random>
#include <vector>

namespace terratin {
namespace {

TEST(TileHandout, WithoutABound_HandsOutEveryTileInOrder_AndCountsTheEarlyOnes) {
    TileHandout handout(4, 0);
    for (std::size_t tile = 0; tile < 4; ++tile)
        EXPECT_EQ(handout.next(), tile);
    EXPECT_TRUE(handout.allHandedOut());
    EXPECT_EQ(handout.next(), std::nullopt);
    handout.back(3, 30);
    handout.back(1, 10);
    EXPECT_EQ(handout.earlyBytes(), 40U);
    handout.back(0, 5); // joins 0 and 1; 3 still waits for 2
    EXPECT_EQ(handout.earlyBytes(), 30U);
    handout.back(2, 20);
    EXPECT_EQ(handout.earlyBytes(), 0U);
    EXPECT_EQ(handout.mostEarlyBytes(), 40U);
}

TEST(TileHandout, EarlyTilesOverTheBound_PauseTheHandout_UntilTheTileInTurnComesBack) {
    TileHandout handout(10, 150);
    for (std::size_t tile = 0; tile < 3; ++tile)
        EXPECT_EQ(handout.next(), tile);
    handout.back(1, 100);
    EXPECT_EQ(handout.next(), 3U); // 100: within the bound
    handout.back(2, 50);
    EXPECT_EQ(handout.next(), 4U); // exactly the bound
    handout.back(3, 1);
    EXPECT_EQ(handout.next(), std::nullopt); // 151
    EXPECT_FALSE(handout.allHandedOut());
    handout.back(0, 1000); // in turn: joined with 1, 2 and 3 at once
    EXPECT_EQ(handout.earlyBytes(), 0U);
    EXPECT_EQ(handout.next(), 5U);
}

TEST(TileHandout, ATileBackTwice_OrNeverHandedOut_IsAnError) {
    TileHandout handout(3, 0);
    EXPECT_THROW(handout.back(0, 1), Error);
    ASSERT_EQ(handout.next(), 0U);
    ASSERT_EQ(handout.next(), 1U);
    handout.back(1, 1);
    EXPECT_THROW(handout.back(1, 1), Error);
    handout.back(0, 1);
    EXPECT_THROW(handout.back(0, 1), Error);
}

TEST(TileHandout, WorkersFinishingInAnyOrder_NeverAllWait_AndTheEarlyBytesStayNearTheBound) {
    // Workers each refine one tile at a time and finish in random order, tiles of random
    // sizes; a worker whose tile is back asks for the next and waits while none is handed out.
    // Whatever the order, the run ends (some worker is always busy while tiles remain), and
    // the early tiles pass the bound by at most what the busy workers bring back.
    constexpr std::uint64_t kBound = 1000;
    constexpr std::uint64_t kLargest = 400;
    std::mt19937 random(25);
    for (const std::size_t workers : {1U, 2U, 7U}) {
        SCOPED_TRACE("workers " + std::to_string(workers));
        constexpr std::size_t kTiles = 200;
        TileHandout handout(kTiles, kBound);
        std::vector<std::size_t> busy; // the tile of each busy worker
        std::size_t idle = workers;
        std::size_t back = 0;
        const auto handOut = [&] {
            while (idle > 0) {
                const std::optional<std::size_t> tile = handout.next();
                if (!tile)
                    return;
                busy.push_back(*tile);
                --idle;
            }
        };
        handOut();
        while (back < kTiles) {
            ASSERT_FALSE(busy.empty()) << "every worker waits with " << kTiles - back << " left";
            const std::size_t finished =
                std::uniform_int_distribution<std::size_t>(0, busy.size() - 1)(random);
            handout.back(busy[finished],
                         std::uniform_int_distribution<std::uint64_t>(1, kLargest)(random));
            busy.erase(busy.begin() + static_cast<std::ptrdiff_t>(finished));
            ++back;
            ++idle;
            handOut();
        }
        EXPECT_TRUE(handout.allHandedOut());
        EXPECT_EQ(handout.earlyBytes(), 0U);
        EXPECT_LE(handout.mostEarlyBytes(), kBound + (workers - 1) * kLargest);
        if (workers > 1) {
            EXPECT_GT(handout.mostEarlyBytes(), 0U);
        }
    }
}

TEST(TileHandout, TilesLeftWithTheirWorkersUntilAccepted_KeepTheEarlyBytesWithinTheBound) {
    // As above, but a finished tile comes back only when accepts() says so (MPI leaves the
    // result unreceived); until then its worker holds it and takes no other tile. The early
    // tiles never pass the bound, and the run still ends: the tile in turn is always accepted.
    constexpr std::uint64_t kBound = 1000;
    constexpr std::uint64_t kLargest = 400;
    std::mt19937 random(26);
    for (const std::size_t workers : {1U, 2U, 7U, 20U}) {
        SCOPED_TRACE("workers " + std::to_string(workers));
        constexpr std::size_t kTiles = 200;
        TileHandout handout(kTiles, kBound);
        struct Work {
            std::size_t tile;
            std::uint64_t bytes;
            bool finished;
        };
        std::vector<Work> busy; // each busy worker's tile, finished or not
        std::size_t idle = workers;
        std::size_t back = 0;
        const auto handOut = [&] {
            while (idle > 0) {
                const std::optional<std::size_t> tile = handout.next();
                if (!tile)
                    return;
                busy.push_back({*tile,
                                std::uniform_int_distribution<std::uint64_t>(1, kLargest)(random),
                                false});
                --idle;
            }
        };
        handOut();
        while (back < kTiles) {
            ASSERT_FALSE(busy.empty()) << "every worker waits with " << kTiles - back << " left";
            // A worker still refining finishes, or a finished one is asked about again.
            Work& work =
                busy[std::uniform_int_distribution<std::size_t>(0, busy.size() - 1)(random)];
            work.finished = true;
            const auto accepted = std::find_if(busy.begin(), busy.end(), [&](const Work& w) {
                return w.finished && handout.accepts(w.tile, w.bytes);
            });
            if (accepted == busy.end()) {
                const bool anyRefining = std::any_of(busy.begin(), busy.end(),
                                                     [](const Work& w) { return !w.finished; });
                ASSERT_TRUE(anyRefining) << "every worker holds a tile none accepts";
                continue;
            }
            handout.back(accepted->tile, accepted->bytes);
            EXPECT_LE(handout.earlyBytes(), kBound);
            busy.erase(accepted);
            ++back;
            ++idle;
            handOut();
        }
        EXPECT_TRUE(handout.allHandedOut());
        EXPECT_EQ(handout.earlyBytes(), 0U);
        EXPECT_LE(handout.mostEarlyBytes(), kBound);
    }
}

} // namespace
} // namespace terratin

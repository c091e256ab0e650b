// ConstraintOwners, the open-addressing table of constrained edges' owners, against std::map
// under random adds and takes (takes empty probe chains through backward shifts); and
// ConstraintChains, whose chains are made from their splits at the end, against chains split at
// once.

#include "constraint_chains.hpp"
#include "constraint_owners.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <map>
#include <random>
#include <stdexcept>
#include <utility>
#include <vector>

namespace terratin::detail {
namespace {

using Edge = std::pair<std::uint32_t, std::uint32_t>;

Edge ordered(std::uint32_t a, std::uint32_t b) {
    return a < b ? Edge{a, b} : Edge{b, a};
}

TEST(ConstraintOwners, AgreesWithAMap_UnderRandomAddsAndTakes) {
    ConstraintOwners owners;
    owners.reserve(10); // it must grow well past this
    std::map<Edge, std::vector<std::uint32_t>> expected;
    std::mt19937_64 random(3);
    // Few vertices: the same edges come back, in either order, and probe chains collide.
    std::uniform_int_distribution<std::uint32_t> vertex(0, 300);
    std::uniform_int_distribution<std::uint32_t> owner(0, 5);
    for (int step = 0; step < 200000; ++step) {
        const std::uint32_t a = vertex(random);
        const std::uint32_t b = vertex(random);
        if (random() % 3 != 0) {
            const std::vector<std::uint32_t> added{owner(random), owner(random)};
            owners.add(a, b, added);
            std::vector<std::uint32_t>& known = expected[ordered(a, b)];
            for (const std::uint32_t o : added)
                if (std::find(known.begin(), known.end(), o) == known.end())
                    known.push_back(o);
        } else {
            std::vector<std::uint32_t> taken = owners.take(b, a);
            std::vector<std::uint32_t> known;
            if (const auto found = expected.find(ordered(a, b)); found != expected.end()) {
                known = found->second;
                expected.erase(found);
            }
            std::sort(taken.begin(), taken.end());
            std::sort(known.begin(), known.end());
            ASSERT_EQ(taken, known) << "step " << step;
        }
    }
    for (const auto& [edge, known] : expected) {
        std::vector<std::uint32_t> taken = owners.take(edge.first, edge.second);
        std::vector<std::uint32_t> sortedKnown = known;
        std::sort(taken.begin(), taken.end());
        std::sort(sortedKnown.begin(), sortedKnown.end());
        EXPECT_EQ(taken, sortedKnown);
    }
    EXPECT_TRUE(owners.take(1, 2).empty());
}

// The edges of a run of new vertices, two and more per vertex by its smaller end, as the
// crossings of many lines make them: more than the two slots a vertex has, so they spill, and
// must still agree with the map (slots in the vertices' order once made one cluster of the whole
// run, which this would walk through at every probe).
TEST(ConstraintOwners, AgreesWithAMap_ForTheEdgesOfARunOfNewVertices) {
    ConstraintOwners owners;
    std::map<Edge, std::vector<std::uint32_t>> expected;
    constexpr std::uint32_t kFirst = 1000000;
    for (std::uint32_t v = kFirst; v < kFirst + 30000; ++v)
        for (const std::uint32_t other : {v + 1, v + 7, v + 30}) {
            owners.add(v, other, {v % 5});
            expected[ordered(v, other)] = {v % 5};
        }
    for (const auto& [edge, known] : expected)
        ASSERT_EQ(owners.take(edge.second, edge.first), known);
    EXPECT_TRUE(owners.empty());
}

/// A chain split at once: w goes between x and y wherever they are consecutive.
void splitAtOnce(std::vector<std::uint32_t>& chain, std::uint32_t x, std::uint32_t y,
                 std::uint32_t w) {
    if (w == x || w == y)
        return;
    for (std::size_t k = 1; k < chain.size(); ++k)
        if ((chain[k - 1] == x && chain[k] == y) || (chain[k - 1] == y && chain[k] == x)) {
            chain.insert(chain.begin() + static_cast<std::ptrdiff_t>(k), w);
            ++k;
        }
}

// Chains of a few splits and of thousands (made through the table of pairs), some splits putting
// back a vertex already on the chain, so that a pair comes twice (rounding among crowded
// crossings does that) and every place of it is split from then on: the same as at once.
TEST(ConstraintChains, MadeFromTheirSplits_AgreeWithChainsSplitAtOnce_WhenPairsComeBack) {
    std::mt19937_64 random(11);
    for (const std::size_t splits :
         {std::size_t{3}, std::size_t{16}, std::size_t{17}, std::size_t{200}, std::size_t{5000}}) {
        for (const bool comeBack : {false, true}) {
            ConstraintChains chains;
            chains.prepare(2);
            chains.start(0, 1, 2);
            chains.start(1, 2, 1); // another owner of the same edge, the other way round
            std::vector<std::uint32_t> expected{1, 2};
            std::uint32_t next = 3;
            for (std::size_t s = 0; s < splits; ++s) {
                const std::size_t k = 1 + random() % (expected.size() - 1);
                const std::uint32_t x = expected[k - 1];
                const std::uint32_t y = expected[k];
                std::uint32_t w = next++;
                if (comeBack && random() % 8 == 0)
                    w = expected[random() % expected.size()];
                chains.insertBetween({0}, x, y, w);
                splitAtOnce(expected, x, y, w);
            }
            EXPECT_EQ(chains.chain(0), expected) << splits << " splits";
            std::vector<std::uint32_t> joined{1};
            chains.appendAfterFirst(0, joined);
            EXPECT_EQ(joined, expected);
            EXPECT_EQ(chains.chain(1), (std::vector<std::uint32_t>{2, 1}));
        }
    }
}

TEST(ConstraintChains, Throws_WhenASplitPairIsNotOnTheChain) {
    for (const std::size_t before : {std::size_t{0}, std::size_t{40}}) {
        ConstraintChains chains;
        chains.start(0, 1, 2);
        std::uint32_t last = 1;
        for (std::uint32_t w = 3; w < 3 + before; ++w) {
            chains.insertBetween({0}, last, 2, w);
            last = w;
        }
        chains.insertBetween({0}, 1, 7000, 9000);
        EXPECT_THROW((void)chains.chain(0), std::logic_error) << before << " splits before";
    }
}

} // namespace
} // namespace terratin::detail

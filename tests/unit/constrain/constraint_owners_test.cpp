// ConstraintOwners, the open-addressing table of constrained edges' owners, against std::map
// under random adds and takes (takes empty probe chains through backward shifts).

#include "constraint_owners.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <map>
#include <random>
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

} // namespace
} // namespace terratin::detail

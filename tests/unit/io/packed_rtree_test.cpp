// PackedRtree: the node blobs in SQLite's R*Tree format hold every entry once, in nodes no
// fuller than the capacity, each cell's box enclosing what lies below it.

#include "packed_rtree.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <map>
#include <optional>
#include <random>
#include <set>
#include <vector>

namespace terratin::io::detail {
namespace {

std::uint64_t bigEndian(const std::uint8_t* bytes, int count) {
    std::uint64_t value = 0;
    for (int i = 0; i < count; ++i)
        value = (value << 8) | bytes[i];
    return value;
}

float bigEndianFloat(const std::uint8_t* bytes) {
    const auto bits = static_cast<std::uint32_t>(bigEndian(bytes, 4));
    float value = 0.0f;
    std::memcpy(&value, &bits, sizeof value);
    return value;
}

struct Cell {
    std::int64_t id = 0;
    RtreeBox box;
};

struct DecodedNode {
    int depth = 0;
    std::int64_t parent = 0;
    std::vector<Cell> cells;
};

std::map<std::int64_t, DecodedNode> decode(const PackedRtree& tree) {
    std::map<std::int64_t, DecodedNode> nodes;
    tree.forEachNode([&](const PackedRtree::Node& node) {
        EXPECT_EQ(node.blob.size(), tree.nodeBytes());
        DecodedNode& decoded = nodes[node.number];
        decoded.depth = static_cast<int>(bigEndian(node.blob.data(), 2));
        decoded.parent = node.parent;
        const auto count = static_cast<int>(bigEndian(node.blob.data() + 2, 2));
        for (int i = 0; i < count; ++i) {
            const std::uint8_t* cell = node.blob.data() + 4 + 24 * i;
            decoded.cells.push_back({static_cast<std::int64_t>(bigEndian(cell, 8)),
                                     {bigEndianFloat(cell + 8), bigEndianFloat(cell + 12),
                                      bigEndianFloat(cell + 16), bigEndianFloat(cell + 20)}});
        }
    });
    return nodes;
}

bool encloses(const RtreeBox& outer, const RtreeBox& inner) {
    return outer.minX <= inner.minX && inner.maxX <= outer.maxX && outer.minY <= inner.minY &&
           inner.maxY <= outer.maxY;
}

std::vector<RtreeBox> randomBoxes(std::size_t count, unsigned seed) {
    std::mt19937_64 random(seed);
    std::uniform_real_distribution<double> position(500000.0, 530000.0);
    std::uniform_real_distribution<double> size(0.0, 40.0);
    std::vector<RtreeBox> boxes;
    for (std::size_t i = 0; i < count; ++i) {
        const double x = position(random);
        const double y = position(random) + 4.5e6;
        boxes.push_back(enclosingRtreeBox(x, x + size(random), y, y + size(random)));
    }
    return boxes;
}

/// Checks the whole structure: node 1 is the root with the tree's depth, leaves hold each id
/// 1..n once at depth 0, every parent link matches the cell that points down, boxes nest, and
/// leafOfEntry names the leaf that holds each id.
void expectWellFormed(const std::vector<RtreeBox>& boxes, int capacity) {
    const PackedRtree tree(boxes, capacity);
    const auto nodes = decode(tree);
    ASSERT_EQ(nodes.size(), tree.nodeCount());
    ASSERT_EQ(nodes.begin()->first, 1);
    EXPECT_EQ(nodes.at(1).parent, 0);

    std::set<std::int64_t> seen;
    std::map<std::int64_t, std::int64_t> leafOf;
    // Walk down from the root, checking each level's boxes against the cell above.
    struct Visit {
        std::int64_t node;
        int level;
        std::optional<RtreeBox> bound;
    };
    std::vector<Visit> stack{{1, nodes.at(1).depth, std::nullopt}};
    std::size_t visited = 0;
    while (!stack.empty()) {
        const Visit visit = stack.back();
        stack.pop_back();
        ++visited;
        const DecodedNode& node = nodes.at(visit.node);
        EXPECT_LE(node.cells.size(), static_cast<std::size_t>(capacity));
        EXPECT_GE(node.cells.size(), 1u);
        if (visit.node != 1) {
            EXPECT_EQ(node.depth, 0) << "only the root stores the depth";
        }
        for (const Cell& cell : node.cells) {
            if (visit.bound) {
                EXPECT_TRUE(encloses(*visit.bound, cell.box));
            }
            if (visit.level == 0) {
                ASSERT_GE(cell.id, 1);
                ASSERT_LE(cell.id, static_cast<std::int64_t>(boxes.size()));
                EXPECT_TRUE(seen.insert(cell.id).second) << "id " << cell.id << " twice";
                const RtreeBox& box = boxes[static_cast<std::size_t>(cell.id - 1)];
                EXPECT_TRUE(encloses(cell.box, box) && encloses(box, cell.box));
                leafOf[cell.id] = visit.node;
            } else {
                ASSERT_TRUE(nodes.count(cell.id));
                EXPECT_EQ(nodes.at(cell.id).parent, visit.node);
                stack.push_back({cell.id, visit.level - 1, cell.box});
            }
        }
    }
    EXPECT_EQ(visited, nodes.size()) << "a node nobody points to";
    EXPECT_EQ(seen.size(), boxes.size());
    const std::vector<std::int64_t> leafOfEntry = tree.leafOfEntry();
    for (std::size_t i = 0; i < boxes.size(); ++i)
        EXPECT_EQ(leafOfEntry[i], leafOf.at(static_cast<std::int64_t>(i) + 1));
}

TEST(PackedRtree, HoldsEveryEntryOnceInNestedNodes_ForManySizes) {
    for (const std::size_t count : {1u, 2u, 50u, 51u, 52u, 2601u, 2602u, 20000u})
        expectWellFormed(randomBoxes(count, static_cast<unsigned>(count)), 51);
}

TEST(PackedRtree, BuildsSeveralLevels_WhenNodesAreSmall) {
    const std::vector<RtreeBox> boxes = randomBoxes(1000, 7);
    expectWellFormed(boxes, 2);
    expectWellFormed(boxes, 3);
    const PackedRtree tree(boxes, 3);
    EXPECT_EQ(decode(tree).at(1).depth, 6); // ceil(log3(1000)) - 1 levels above the leaves
}

TEST(PackedRtree, HasNoNodes_WhenEmpty) {
    const PackedRtree tree({}, 51);
    EXPECT_EQ(tree.nodeCount(), 0u);
    EXPECT_TRUE(tree.leafOfEntry().empty());
}

TEST(PackedRtree, EnclosingBoxRoundsOutwards_WhenDoublesAreNotFloats) {
    // 5 000 000.3 lies between two floats (0.5 apart there): the box must contain it.
    const RtreeBox box = enclosingRtreeBox(512345.37, 512345.37, 5000000.3, 5000000.3);
    EXPECT_LE(static_cast<double>(box.minX), 512345.37);
    EXPECT_GE(static_cast<double>(box.maxX), 512345.37);
    EXPECT_LE(static_cast<double>(box.minY), 5000000.3);
    EXPECT_GE(static_cast<double>(box.maxY), 5000000.3);
    EXPECT_LT(box.minY, box.maxY);
    // A value a float holds exactly stays as it is.
    const RtreeBox exact = enclosingRtreeBox(1.5, 2.0, -3.25, 4.0);
    EXPECT_EQ(exact.minX, 1.5f);
    EXPECT_EQ(exact.maxX, 2.0f);
    EXPECT_EQ(exact.minY, -3.25f);
    EXPECT_EQ(exact.maxY, 4.0f);
}

TEST(PackedRtree, NodeSizeFollowsSqlite_ForPageSizes) {
    for (const int page : {4096, 65536}) {
        EXPECT_EQ(RtreeNodeSize::forPage(page).capacity, 51);
        EXPECT_EQ(RtreeNodeSize::forPage(page).bytes, 1228u); // 4 + 51 * 24
    }
    EXPECT_EQ(RtreeNodeSize::forPage(1024).capacity, 39); // (1024 - 64 - 4) / 24
    EXPECT_EQ(RtreeNodeSize::forPage(1024).bytes, 960u);  // the page less 64, padded
    // 512-byte pages: SQLite refuses node blobs under 448 bytes, so 18 cells (436 bytes) are
    // padded to the page less 64.
    EXPECT_EQ(RtreeNodeSize::forPage(512).capacity, 18);
    EXPECT_EQ(RtreeNodeSize::forPage(512).bytes, 448u);
}

} // namespace
} // namespace terratin::io::detail

#pragma once
/// @file
/// PackedRtree: an R-tree packed bottom-up by sort-tile-recursive (Leutenegger, Lopez and
/// Edgington, "STR: a simple and efficient algorithm for R-tree packing", ICDE 1997), laid out
/// as SQLite's R*Tree module stores it, so that it can be written straight into the module's
/// shadow tables instead of being inserted one entry at a time.
///
/// SQLite's format (ext/rtree/rtree.c): a node is a blob of the table's node size (at least
/// `4 + capacity * 24` bytes, the rest zero), a big-endian u16 depth (root only; 0 elsewhere) and
/// u16 cell count, then per cell a big-endian i64 id (feature id in a leaf, child node number
/// above) and minx, maxx, miny, maxy as big-endian float32. The root is node 1.

#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

namespace terratin::io::detail {

/// A box in the float32 coordinates SQLite's R*Tree keeps: rounded outwards, so that it
/// encloses the double-precision box it stands for.
struct RtreeBox {
    float minX = 0.0f;
    float maxX = 0.0f;
    float minY = 0.0f;
    float maxY = 0.0f;
};

/// The RtreeBox of [minX, maxX] x [minY, maxY]: minima rounded down, maxima up.
RtreeBox enclosingRtreeBox(double minX, double maxX, double minY, double maxY);

/// The nodes of one R*Tree table: every node blob has the same size, which SQLite reads back
/// from the root when it opens the table (and refuses under 448 bytes as "undersize RTree
/// blobs").
struct RtreeNodeSize {
    /// Cells per node.
    int capacity = 0;
    /// Bytes per node blob.
    std::size_t bytes = 0;

    /// The size SQLite's R*Tree module gives a new table on pages of `pageBytes`: the page
    /// less 64 bytes, at most 51 cells (4 + 51 * 24 bytes), and as many cells as fit in that.
    static RtreeNodeSize forPage(int pageBytes);
    /// Exactly `capacity` cells, no padding.
    static RtreeNodeSize forCapacity(int capacity);
};

/// The packed tree of `boxes`, where boxes[i] is the box of feature id i + 1.
class PackedRtree {
public:
    /// Packs `boxes` (moved in) into nodes of `nodeSize` (2 cells or more).
    PackedRtree(std::vector<RtreeBox> boxes, RtreeNodeSize nodeSize);
    /// Packs `boxes` with `capacity` cells per node, unpadded.
    PackedRtree(std::vector<RtreeBox> boxes, int capacity)
        : PackedRtree(std::move(boxes), RtreeNodeSize::forCapacity(capacity)) {}

    [[nodiscard]] std::size_t entryCount() const { return m_boxes.size(); }
    [[nodiscard]] std::size_t nodeCount() const { return m_nodeCount; }
    [[nodiscard]] int capacity() const { return m_capacity; }
    [[nodiscard]] std::size_t nodeBytes() const { return m_nodeBytes; }

    /// One stored node: its number, its blob, and its parent's number (0 for the root).
    struct Node {
        std::int64_t number = 0;
        std::int64_t parent = 0;
        std::vector<std::uint8_t> blob;
    };
    /// Calls visit(const Node&) for every node, root first. Not for an empty tree.
    template <class Visit> void forEachNode(Visit&& visit) const;

    /// leafOfEntry()[i]: number of the leaf node holding feature id i + 1.
    [[nodiscard]] std::vector<std::int64_t> leafOfEntry() const;

private:
    /// Level k groups the items of level k - 1 (level 0 groups the entries) into nodes:
    /// node j of level k holds items order[j * capacity ...], at most capacity of them.
    struct Level {
        std::vector<std::uint32_t> order;
        std::vector<RtreeBox> nodeBoxes;
        /// Node j's number is firstNumber + j; numbers run root first, level by level.
        std::int64_t firstNumber = 0;
        /// Index, in the level above, of node j's parent (empty at the root).
        std::vector<std::uint32_t> parentOf;
    };

    void fillNode(std::size_t level, std::size_t node, Node& out) const;

    std::vector<RtreeBox> m_boxes;
    int m_capacity;
    std::size_t m_nodeBytes;
    std::vector<Level> m_levels;
    std::size_t m_nodeCount = 0;
};

template <class Visit> void PackedRtree::forEachNode(Visit&& visit) const {
    Node node;
    for (std::size_t level = m_levels.size(); level-- > 0;)
        for (std::size_t j = 0; j < m_levels[level].nodeBoxes.size(); ++j) {
            fillNode(level, j, node);
            visit(static_cast<const Node&>(node));
        }
}

} // namespace terratin::io::detail

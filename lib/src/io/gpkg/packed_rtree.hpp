#pragma once
/// @file
/// PackedRtree: an R-tree packed bottom-up by sort-tile-recursive (Leutenegger, Lopez and
/// Edgington, "STR: a simple and efficient algorithm for R-tree packing", ICDE 1997), laid out
/// as SQLite's R*Tree module stores it, so that it can be written straight into the module's
/// shadow tables instead of being inserted one entry at a time.
///
/// SQLite's format (ext/rtree/rtree.c): a node is a blob of `4 + capacity * 24` bytes, a
/// big-endian u16 depth (root only; 0 elsewhere) and u16 cell count, then per cell a big-endian
/// i64 id (feature id in a leaf, child node number above) and minx, maxx, miny, maxy as
/// big-endian float32. The root is node 1.

#include <cstddef>
#include <cstdint>
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

/// Cells per node for a database page of `pageBytes`: as many as fit in a page less 64 bytes,
/// at most 51 (the limits SQLite's R*Tree module applies when it creates a table).
int rtreeNodeCapacity(int pageBytes);

/// Node bytes for `capacity` cells.
inline std::size_t rtreeNodeBytes(int capacity) {
    return 4 + static_cast<std::size_t>(capacity) * 24;
}

/// The packed tree of `boxes`, where boxes[i] is the box of feature id i + 1.
class PackedRtree {
public:
    /// Packs `boxes` (moved in) with `capacity` cells per node (2 or more).
    PackedRtree(std::vector<RtreeBox> boxes, int capacity);

    [[nodiscard]] std::size_t entryCount() const { return m_boxes.size(); }
    [[nodiscard]] std::size_t nodeCount() const { return m_nodeCount; }
    [[nodiscard]] int capacity() const { return m_capacity; }

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

#include "packed_rtree.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>

namespace terratin::io::detail {

namespace {

/// SQLite's R*Tree keeps at most this many cells in a node (RTREE_MAXCELLS in rtree.c).
constexpr int kMaxCells = 51;
/// Bytes per 2D cell: an i64 id and four float32 coordinates.
constexpr int kCellBytes = 24;
/// SQLite's R*Tree leaves this much of a page for the row around the node blob.
constexpr int kPageReserveBytes = 64;
/// A node's depth and cell count, two u16.
constexpr int kNodeHeaderBytes = 4;

float roundedDown(double value) {
    float rounded = static_cast<float>(value);
    if (static_cast<double>(rounded) > value)
        rounded = std::nextafter(rounded, -std::numeric_limits<float>::infinity());
    return rounded;
}

float roundedUp(double value) {
    float rounded = static_cast<float>(value);
    if (static_cast<double>(rounded) < value)
        rounded = std::nextafter(rounded, std::numeric_limits<float>::infinity());
    return rounded;
}

RtreeBox unite(const RtreeBox& a, const RtreeBox& b) {
    return {std::min(a.minX, b.minX), std::max(a.maxX, b.maxX), std::min(a.minY, b.minY),
            std::max(a.maxY, b.maxY)};
}

float centreX(const RtreeBox& box) {
    return box.minX * 0.5f + box.maxX * 0.5f;
}
float centreY(const RtreeBox& box) {
    return box.minY * 0.5f + box.maxY * 0.5f;
}

/// Sort-tile-recursive order of `boxes`: sorted by centre x, cut into about sqrt(nodes)
/// vertical slices of whole nodes, each slice sorted by centre y. Consecutive runs of
/// `capacity` items of the result are the nodes of the level above.
std::vector<std::uint32_t> strOrder(const std::vector<RtreeBox>& boxes, int capacity) {
    std::vector<std::uint32_t> order(boxes.size());
    for (std::uint32_t i = 0; i < order.size(); ++i)
        order[i] = i;
    const auto byX = [&](std::uint32_t a, std::uint32_t b) {
        return centreX(boxes[a]) < centreX(boxes[b]);
    };
    const auto byY = [&](std::uint32_t a, std::uint32_t b) {
        return centreY(boxes[a]) < centreY(boxes[b]);
    };
    std::sort(order.begin(), order.end(), byX);
    const std::size_t cap = static_cast<std::size_t>(capacity);
    const std::size_t nodes = (boxes.size() + cap - 1) / cap;
    const auto slices = static_cast<std::size_t>(std::ceil(std::sqrt(static_cast<double>(nodes))));
    const std::size_t sliceItems = ((nodes + slices - 1) / slices) * cap;
    for (std::size_t begin = 0; begin < order.size(); begin += sliceItems) {
        const std::size_t end = std::min(order.size(), begin + sliceItems);
        std::sort(order.begin() + static_cast<std::ptrdiff_t>(begin),
                  order.begin() + static_cast<std::ptrdiff_t>(end), byY);
    }
    return order;
}

void putBigEndian16(std::uint8_t* out, std::uint16_t value) {
    out[0] = static_cast<std::uint8_t>(value >> 8);
    out[1] = static_cast<std::uint8_t>(value);
}

void putBigEndian32(std::uint8_t* out, std::uint32_t value) {
    for (int i = 0; i < 4; ++i)
        out[i] = static_cast<std::uint8_t>(value >> (24 - 8 * i));
}

void putBigEndian64(std::uint8_t* out, std::uint64_t value) {
    for (int i = 0; i < 8; ++i)
        out[i] = static_cast<std::uint8_t>(value >> (56 - 8 * i));
}

void putFloat(std::uint8_t* out, float value) {
    std::uint32_t bits = 0;
    std::memcpy(&bits, &value, sizeof bits);
    putBigEndian32(out, bits);
}

void putCell(std::uint8_t* out, std::int64_t id, const RtreeBox& box) {
    putBigEndian64(out, static_cast<std::uint64_t>(id));
    putFloat(out + 8, box.minX);
    putFloat(out + 12, box.maxX);
    putFloat(out + 16, box.minY);
    putFloat(out + 20, box.maxY);
}

} // namespace

RtreeBox enclosingRtreeBox(double minX, double maxX, double minY, double maxY) {
    return {roundedDown(minX), roundedUp(maxX), roundedDown(minY), roundedUp(maxY)};
}

RtreeNodeSize RtreeNodeSize::forPage(int pageBytes) {
    const int bytes =
        std::min(pageBytes - kPageReserveBytes, kNodeHeaderBytes + kMaxCells * kCellBytes);
    return {(bytes - kNodeHeaderBytes) / kCellBytes, static_cast<std::size_t>(bytes)};
}

RtreeNodeSize RtreeNodeSize::forCapacity(int capacity) {
    return {capacity, static_cast<std::size_t>(kNodeHeaderBytes + capacity * kCellBytes)};
}

PackedRtree::PackedRtree(std::vector<RtreeBox> boxes, RtreeNodeSize nodeSize)
    : m_boxes(std::move(boxes)), m_capacity(nodeSize.capacity), m_nodeBytes(nodeSize.bytes) {
    const int capacity = m_capacity;
    if (capacity < 2 || m_nodeBytes < RtreeNodeSize::forCapacity(capacity).bytes)
        throw std::invalid_argument("PackedRtree: a node needs room for two cells");
    if (m_boxes.size() > std::numeric_limits<std::uint32_t>::max())
        throw std::invalid_argument("PackedRtree: more than 2^32 entries");
    if (m_boxes.empty())
        return;
    // Bottom-up: each level packs the boxes of the one below until one node is left.
    const std::vector<RtreeBox>* items = &m_boxes;
    const auto cap = static_cast<std::size_t>(capacity);
    do {
        Level level;
        level.order = strOrder(*items, capacity);
        for (std::size_t begin = 0; begin < level.order.size(); begin += cap) {
            const std::size_t end = std::min(level.order.size(), begin + cap);
            RtreeBox box = (*items)[level.order[begin]];
            for (std::size_t i = begin + 1; i < end; ++i)
                box = unite(box, (*items)[level.order[i]]);
            level.nodeBoxes.push_back(box);
        }
        m_levels.push_back(std::move(level));
        items = &m_levels.back().nodeBoxes;
    } while (items->size() > 1);

    // Numbers root first, level by level; each node learns its parent from the level above.
    std::int64_t next = 1;
    for (std::size_t k = m_levels.size(); k-- > 0;) {
        m_levels[k].firstNumber = next;
        next += static_cast<std::int64_t>(m_levels[k].nodeBoxes.size());
        if (k + 1 < m_levels.size()) {
            const Level& above = m_levels[k + 1];
            m_levels[k].parentOf.resize(m_levels[k].nodeBoxes.size());
            for (std::size_t position = 0; position < above.order.size(); ++position)
                m_levels[k].parentOf[above.order[position]] =
                    static_cast<std::uint32_t>(position / cap);
        }
    }
    m_nodeCount = static_cast<std::size_t>(next - 1);
}

void PackedRtree::fillNode(std::size_t level, std::size_t node, Node& out) const {
    const Level& here = m_levels[level];
    const auto cap = static_cast<std::size_t>(m_capacity);
    const std::size_t begin = node * cap;
    const std::size_t end = std::min(here.order.size(), begin + cap);
    const bool isRoot = level + 1 == m_levels.size();

    out.number = here.firstNumber + static_cast<std::int64_t>(node);
    out.parent =
        isRoot ? 0
               : m_levels[level + 1].firstNumber + static_cast<std::int64_t>(here.parentOf[node]);
    out.blob.assign(m_nodeBytes, 0);
    putBigEndian16(out.blob.data(), isRoot ? static_cast<std::uint16_t>(level) : 0);
    putBigEndian16(out.blob.data() + 2, static_cast<std::uint16_t>(end - begin));
    std::uint8_t* cell = out.blob.data() + 4;
    for (std::size_t i = begin; i < end; ++i, cell += kCellBytes) {
        const std::uint32_t item = here.order[i];
        if (level == 0)
            putCell(cell, static_cast<std::int64_t>(item) + 1, m_boxes[item]);
        else
            putCell(cell, m_levels[level - 1].firstNumber + item,
                    m_levels[level - 1].nodeBoxes[item]);
    }
}

std::vector<std::int64_t> PackedRtree::leafOfEntry() const {
    std::vector<std::int64_t> leafOf(m_boxes.size());
    if (m_levels.empty())
        return leafOf;
    const Level& leaves = m_levels.front();
    const auto cap = static_cast<std::size_t>(m_capacity);
    for (std::size_t position = 0; position < leaves.order.size(); ++position)
        leafOf[leaves.order[position]] =
            leaves.firstNumber + static_cast<std::int64_t>(position / cap);
    return leafOf;
}

} // namespace terratin::io::detail

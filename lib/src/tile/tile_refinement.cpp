#include "tile_refinement.hpp"

#include "terratin/error.hpp"

#include <cstdint>
#include <cstring>

namespace terratin::detail {

namespace {

/// Appends trivially copyable values to a byte vector, raw: both ends are the same build.
class Packer {
public:
    template <class T> void value(const T& value) { raw(&value, sizeof value); }
    template <class Array> void array(const Array& values) {
        value(std::uint64_t{values.size()});
        raw(values.data(), values.size() * sizeof(typename Array::value_type));
    }
    std::vector<std::byte> take() { return std::move(m_bytes); }

private:
    void raw(const void* data, std::size_t size) {
        const auto* first = static_cast<const std::byte*>(data);
        m_bytes.insert(m_bytes.end(), first, first + size);
    }
    std::vector<std::byte> m_bytes;
};

class Unpacker {
public:
    explicit Unpacker(const std::vector<std::byte>& bytes) : m_bytes(&bytes) {}
    template <class T> void value(T& value) { raw(&value, sizeof value); }
    template <class Array> void array(Array& values) {
        std::uint64_t size = 0;
        value(size);
        if (size > (m_bytes->size() - m_at) / sizeof(typename Array::value_type))
            truncated();
        values.resize(size);
        raw(values.data(), size * sizeof(typename Array::value_type));
    }
    void expectEnd() const {
        if (m_at != m_bytes->size())
            truncated();
    }

private:
    [[noreturn]] static void truncated() {
        throw Error("Tiles: a tile's TIN came back damaged (its bytes do not add up)");
    }
    void raw(void* data, std::size_t size) {
        if (size > m_bytes->size() - m_at)
            truncated();
        if (size > 0)
            std::memcpy(data, m_bytes->data() + m_at, size);
        m_at += size;
    }
    const std::vector<std::byte>* m_bytes;
    std::size_t m_at = 0;
};

/// Every field of a TileRefinement, in one order for both directions.
template <class Visitor, class Tile> void visitTile(Visitor& visitor, Tile& tile) {
    visitor.value(tile.maxError);
    visitor.value(tile.stop);
    visitor.value(tile.sumSquares);
    for (auto* count :
         {&tile.validCells, &tile.openHoleCells, &tile.coveredCells, &tile.droppedTriangles,
          &tile.hullPoints, &tile.strips, &tile.levels, &tile.deferredCandidates,
          &tile.pairInsertions, &tile.sharedInsertions, &tile.meshBytes})
        visitor.value(*count);
    visitor.array(tile.mesh.vertices);
    visitor.array(tile.mesh.sourceIndex);
    visitor.array(tile.mesh.triangles);
    visitor.array(tile.mesh.neighbours);
    visitor.array(tile.coveredForLaterTiles);
    visitor.array(tile.uncoveredSharedSides);
}

} // namespace

std::vector<std::byte> packTile(const TileRefinement& tile) {
    Packer packer;
    visitTile(packer, tile);
    return packer.take();
}

TileRefinement unpackTile(const std::vector<std::byte>& bytes) {
    TileRefinement tile;
    Unpacker unpacker(bytes);
    visitTile(unpacker, tile);
    unpacker.expectEnd();
    return tile;
}

} // namespace terratin::detail

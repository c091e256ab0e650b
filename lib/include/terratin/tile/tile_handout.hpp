#pragma once
/// @file
/// For a TileDistribution's coordinator: which tile to hand out next. Tiles go out in order,
/// and are joined in order; one that comes back before its turn waits for it in the
/// coordinator's memory. TileHandout counts those early tiles' bytes and hands out no more
/// tiles while they hold more than a bound (so that the coordinator keeps to --memory-limit),
/// and says which tiles may come back within it (accepts). The first tile not back yet is
/// always out in work and always accepted, so a pause always ends.

#include <cstddef>
#include <cstdint>
#include <map>
#include <optional>

namespace terratin {

class TileHandout {
public:
    /// Tiles 0 .. tileCount - 1; `earlyBytes` the bound on the early tiles' bytes (0: none).
    TileHandout(std::size_t tileCount, std::uint64_t earlyBytes);

    /// The tile to hand out now, or nullopt: every tile is out, or the early tiles hold more
    /// than the bound (a rank asking then waits until tiles come back in turn).
    [[nodiscard]] std::optional<std::size_t> next();
    [[nodiscard]] bool allHandedOut() const { return m_handedOut == m_tileCount; }

    /// Whether tile `tile` may come back now as `bytes` bytes: it is the tile in turn (joined at
    /// once), or the early tiles stay within the bound with it. A transport that can leave a
    /// tile with its rank (MPI: the result not received yet) does so until it may, so that the
    /// early tiles never pass the bound.
    [[nodiscard]] bool accepts(std::size_t tile, std::uint64_t bytes) const {
        return tile == m_nextInTurn || m_bound == 0 || m_earlyBytes + bytes <= m_bound;
    }

    /// Tile `tile` (handed out, each once) came back as `bytes` bytes.
    void back(std::size_t tile, std::uint64_t bytes);

    /// What the early tiles hold now, and the most they held.
    [[nodiscard]] std::uint64_t earlyBytes() const { return m_earlyBytes; }
    [[nodiscard]] std::uint64_t mostEarlyBytes() const { return m_mostEarlyBytes; }

private:
    std::size_t m_tileCount;
    std::uint64_t m_bound;
    std::size_t m_handedOut = 0;
    /// The first tile not back yet: every tile before it is joined.
    std::size_t m_nextInTurn = 0;
    std::map<std::size_t, std::uint64_t> m_early;
    std::uint64_t m_earlyBytes = 0;
    std::uint64_t m_mostEarlyBytes = 0;
};

} // namespace terratin

#include "terratin/tile/tile_handout.hpp"

#include "terratin/error.hpp"

#include <algorithm>
#include <string>

namespace terratin {

TileHandout::TileHandout(std::size_t tileCount, std::uint64_t earlyBytes)
    : m_tileCount(tileCount), m_bound(earlyBytes) {}

std::optional<std::size_t> TileHandout::next() {
    if (allHandedOut() || (m_bound > 0 && m_earlyBytes > m_bound))
        return std::nullopt;
    return m_handedOut++;
}

void TileHandout::back(std::size_t tile, std::uint64_t bytes) {
    if (tile >= m_handedOut || tile < m_nextInTurn || m_early.count(tile) != 0)
        throw Error("Tiles: tile " + std::to_string(tile) + " came back without being out in work");
    if (tile != m_nextInTurn) {
        m_early.emplace(tile, bytes);
        m_earlyBytes += bytes;
        m_mostEarlyBytes = std::max(m_mostEarlyBytes, m_earlyBytes);
        return;
    }
    ++m_nextInTurn;
    for (auto early = m_early.find(m_nextInTurn); early != m_early.end();
         early = m_early.find(m_nextInTurn)) {
        m_earlyBytes -= early->second;
        m_early.erase(early);
        ++m_nextInTurn;
    }
}

} // namespace terratin

#include "joined_vertex_numbers.hpp"

namespace terratin::detail {

JoinedVertexNumbers::Number JoinedVertexNumbers::number(std::uint32_t cell,
                                                        const TilePlace& place) {
    const std::size_t row = cell / m_gridWidth - place.firstRow;
    const std::size_t column = cell % m_gridWidth - place.firstColumn;
    const bool onSide =
        row == 0 || column == 0 || row + 1 == place.height || column + 1 == place.width;
    if (onSide) {
        const auto [found, added] = m_sideVertices.emplace(cell, m_count);
        if (!added)
            return {found->second, false};
    }
    return {m_count++, true};
}

} // namespace terratin::detail

#include "terratin/tile/cell_source.hpp"

#include <algorithm>
#include <cstddef>
#include <stdexcept>

namespace terratin {

HeightGrid GridCells::window(int firstRow, int rows, int firstColumn, int columns) {
    if (firstRow < 0 || firstColumn < 0 || rows < 1 || columns < 1 ||
        firstRow + rows > m_grid->height || firstColumn + columns > m_grid->width)
        throw std::out_of_range("GridCells: a window outside the grid");
    HeightGrid window;
    window.width = columns;
    window.height = rows;
    window.geoTransform = m_grid->geoTransform;
    window.firstRow = m_grid->firstRow + firstRow;
    window.firstColumn = m_grid->firstColumn + firstColumn;
    window.z.resize(window.cellCount());
    const auto gridWidth = static_cast<std::size_t>(m_grid->width);
    for (int row = 0; row < rows; ++row) {
        const auto from =
            m_grid->z.begin() +
            static_cast<std::ptrdiff_t>(static_cast<std::size_t>(firstRow + row) * gridWidth +
                                        static_cast<std::size_t>(firstColumn));
        std::copy(from, from + columns,
                  window.z.begin() + static_cast<std::ptrdiff_t>(row) * columns);
    }
    return window;
}

} // namespace terratin

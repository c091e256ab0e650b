#include "terratin/geometry/height_grid.hpp"

namespace terratin {

std::size_t HeightGrid::validCount() const {
    std::size_t count = 0;
    for (const float value : z)
        count += std::isnan(value) ? 0U : 1U;
    return count;
}

} // namespace terratin

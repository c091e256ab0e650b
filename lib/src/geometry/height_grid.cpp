#include "terratin/geometry/height_grid.hpp"

#include "terratin/number_text.hpp"

#include <algorithm>

namespace terratin {

std::size_t HeightGrid::validCount() const {
    std::size_t count = 0;
    for (const float value : z)
        count += std::isnan(value) ? 0U : 1U;
    return count;
}

void HeightGrid::storeElevations(std::size_t firstCell, std::span<const double> elevations) {
    // NaN stays NaN (no data) in float32.
    float* out = z.data() + firstCell;
    for (std::size_t i = 0; i < elevations.size(); ++i)
        out[i] = static_cast<float>(elevations[i]);
}

std::string geoTransformProblem(const std::array<double, 6>& c, std::int64_t width,
                                std::int64_t height) {
    if (!std::all_of(c.begin(), c.end(), [](double v) { return std::isfinite(v); }))
        return "has a coefficient that is not a finite number";
    const double area = c[1] * c[5] - c[2] * c[4];
    if (area == 0.0 || !std::isfinite(area))
        return area == 0.0 ? "gives cells of zero area" : "gives cells of infinite area";
    for (const double row : {0.5, static_cast<double>(height) - 0.5})
        for (const double col : {0.5, static_cast<double>(width) - 0.5}) {
            const double x = c[0] + col * c[1] + row * c[2];
            const double y = c[3] + col * c[4] + row * c[5];
            if (!(std::abs(x) <= kMaxGeoCoordinate && std::abs(y) <= kMaxGeoCoordinate))
                return "puts cell centres beyond 1e15 CRS units from the origin";
        }
    return {};
}

std::string geoTransformText(const std::array<double, 6>& c) {
    std::string text = "(";
    for (std::size_t i = 0; i < c.size(); ++i)
        text += (i == 0 ? "" : ", ") + numberText(c[i]);
    return text + ")";
}

} // namespace terratin

#include "terratin/geometry/height_grid.hpp"

#include "../number_text.hpp"
#include "terratin/geometry/predicates.hpp"

#include <algorithm>
#include <limits>

namespace terratin {

using terratin::detail::numberText;

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

namespace {

/// `p`'s fractional (col, row) in cell-centre units: cell (r, c) is at (c, r).
Point2 fractionalCell(const HeightGrid& grid, Point2 p) {
    const std::array<double, 6>& c = grid.geoTransform;
    const double det = c[1] * c[5] - c[2] * c[4];
    const double dx = p.x - c[0];
    const double dy = p.y - c[3];
    return {(c[5] * dx - c[2] * dy) / det - 0.5 - static_cast<double>(grid.firstColumn),
            (c[1] * dy - c[4] * dx) / det - 0.5 - static_cast<double>(grid.firstRow)};
}

/// The first of two neighbouring indices whose span holds `at`, within 0 .. count - 1; -1 when
/// none does (count < 2, or outside).
std::int64_t spanStart(double at, int count) {
    if (!(at >= 0.0) || at > static_cast<double>(count - 1) || count < 2)
        return -1;
    return std::min(static_cast<std::int64_t>(at), std::int64_t{count} - 2);
}

} // namespace

double bilinearElevation(const HeightGrid& grid, Point2 p) {
    constexpr double kNoValue = std::numeric_limits<double>::quiet_NaN();
    const Point2 at = fractionalCell(grid, p);
    const std::int64_t col = spanStart(at.x, grid.width);
    const std::int64_t row = spanStart(at.y, grid.height);
    if (col < 0 || row < 0)
        return kNoValue;
    const auto cell = [&](std::int64_t r, std::int64_t c) {
        return static_cast<std::size_t>(r) * static_cast<std::size_t>(grid.width) +
               static_cast<std::size_t>(c);
    };
    const std::array<std::size_t, 4> cells{cell(row, col), cell(row, col + 1),
                                           cell(row + 1, col + 1), cell(row + 1, col)};
    std::array<Point2, 4> centres;
    for (std::size_t i = 0; i < 4; ++i) {
        if (!grid.isValid(cells[i]))
            return kNoValue;
        centres[i] = grid.cellCentre(cells[i]);
    }
    // The quadrilateral turns one way or the other with the geotransform's sign.
    const double turn = predicates::orient2d(centres[0], centres[1], centres[2]) > 0.0 ? 1.0 : -1.0;
    for (std::size_t i = 0; i < 4; ++i)
        if (turn * predicates::orient2d(centres[i], centres[(i + 1) % 4], p) < 0.0)
            return kNoValue;
    const double fx = std::clamp(at.x - static_cast<double>(col), 0.0, 1.0);
    const double fy = std::clamp(at.y - static_cast<double>(row), 0.0, 1.0);
    const auto z = [&](std::size_t i) { return static_cast<double>(grid.z[cells[i]]); };
    return (1.0 - fy) * ((1.0 - fx) * z(0) + fx * z(1)) + fy * ((1.0 - fx) * z(3) + fx * z(2));
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

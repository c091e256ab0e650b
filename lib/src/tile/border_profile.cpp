#include "border_profile.hpp"

#include "../refine/error_measure.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

namespace terratin::detail {

namespace {

/// z at `index` on the line through (first, zFirst) and (last, zLast).
double lineAt(std::size_t first, double zFirst, std::size_t last, double zLast, std::size_t index) {
    const double t = static_cast<double>(index - first) / static_cast<double>(last - first);
    return zFirst + (zLast - zFirst) * t;
}

/// Keeps the cells of the valid run [first, last] that the split needs, `first` and `last`
/// excluded (the caller keeps them). An explicit stack: a staircase profile would recurse once
/// per cell.
void splitRun(std::span<const float> z, std::size_t first, std::size_t last, double maxError,
              std::vector<std::uint32_t>& kept) {
    std::vector<std::pair<std::size_t, std::size_t>> pieces{{first, last}};
    while (!pieces.empty()) {
        const auto [a, b] = pieces.back();
        pieces.pop_back();
        std::size_t worst = a;
        double worstError = maxError;
        for (std::size_t i = a + 1; i < b; ++i) {
            const double error = cellError(z[i], lineAt(a, z[a], b, z[b], i));
            if (error > worstError) { // the first of equal errors: the result is fixed
                worst = i;
                worstError = error;
            }
        }
        if (worst == a)
            continue;
        kept.push_back(static_cast<std::uint32_t>(worst));
        pieces.emplace_back(a, worst);
        pieces.emplace_back(worst, b);
    }
}

} // namespace

std::vector<std::uint32_t> keptBorderCells(std::span<const float> elevations, double maxError) {
    if (!std::isfinite(maxError) || maxError < 0.0)
        throw std::invalid_argument("keptBorderCells: maxError must be finite and not negative");
    std::vector<std::uint32_t> kept;
    std::size_t i = 0;
    while (i < elevations.size()) {
        if (std::isnan(elevations[i])) {
            ++i;
            continue;
        }
        std::size_t last = i;
        while (last + 1 < elevations.size() && !std::isnan(elevations[last + 1]))
            ++last;
        kept.push_back(static_cast<std::uint32_t>(i));
        if (last > i) {
            kept.push_back(static_cast<std::uint32_t>(last));
            splitRun(elevations, i, last, maxError, kept);
        }
        i = last + 1;
    }
    std::sort(kept.begin(), kept.end());
    return kept;
}

double borderProfileError(std::span<const float> elevations, std::span<const std::uint32_t> kept) {
    double largest = 0.0;
    for (std::size_t k = 0; k + 1 < kept.size(); ++k) {
        const std::size_t a = kept[k];
        const std::size_t b = kept[k + 1];
        for (std::size_t i = a + 1; i < b; ++i) {
            if (std::isnan(elevations[i]))
                break; // a run ends between a and b: nothing spans the gap
            largest = std::max(
                largest, cellError(elevations[i], lineAt(a, elevations[a], b, elevations[b], i)));
        }
    }
    return largest;
}

} // namespace terratin::detail

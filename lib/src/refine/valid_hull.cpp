#include "valid_hull.hpp"

#include "terratin/error.hpp"
#include "terratin/geometry/predicates.hpp"

#include <algorithm>
#include <cmath>

namespace terratin::detail {

namespace {

struct Candidate {
    Point2 p;
    std::uint32_t cell;
};

// Each row's first and last valid cell.
std::vector<Candidate> rowEnds(const HeightGrid& grid) {
    std::vector<Candidate> candidates;
    const auto width = static_cast<std::size_t>(grid.width);
    for (std::size_t row = 0; row < static_cast<std::size_t>(grid.height); ++row) {
        const float* z = grid.z.data() + row * width;
        std::size_t first = 0;
        while (first < width && std::isnan(z[first]))
            ++first;
        if (first == width)
            continue;
        std::size_t last = width - 1;
        while (std::isnan(z[last]))
            --last;
        for (const std::size_t col : {first, last}) {
            const auto cell = static_cast<std::uint32_t>(row * width + col);
            candidates.push_back({grid.cellCentre(cell), cell});
            if (first == last)
                break;
        }
    }
    return candidates;
}

// The valid cells on the boundary of the valid area (a 4-neighbour outside or nodata), at
// `positions`, or at their cell centres when it is empty.
std::vector<Candidate> boundaryCells(const HeightGrid& grid, std::span<const Point2> positions) {
    std::vector<Candidate> candidates;
    const std::int64_t width = grid.width;
    const std::int64_t height = grid.height;
    const auto valid = [&](std::int64_t row, std::int64_t col) {
        return row >= 0 && col >= 0 && row < height && col < width &&
               grid.isValid(static_cast<std::size_t>(row * width + col));
    };
    for (std::int64_t row = 0; row < height; ++row)
        for (std::int64_t col = 0; col < width; ++col) {
            if (!valid(row, col))
                continue;
            if (valid(row - 1, col) && valid(row + 1, col) && valid(row, col - 1) &&
                valid(row, col + 1))
                continue;
            const auto cell = static_cast<std::uint32_t>(row * width + col);
            candidates.push_back(
                {positions.empty() ? grid.cellCentre(cell) : positions[cell], cell});
        }
    return candidates;
}

} // namespace

std::vector<std::uint32_t> validHullCells(const HeightGrid& grid,
                                          std::span<const Point2> positions) {
    // Rows are exactly horizontal lines only when GT[4] is 0 (see the header); GT[2] alone
    // keeps them so, but is rare enough that the general candidates cost nothing noticeable.
    const bool northUp = grid.geoTransform[2] == 0.0 && grid.geoTransform[4] == 0.0;
    std::vector<Candidate> candidates =
        positions.empty() && northUp ? rowEnds(grid) : boundaryCells(grid, positions);
    if (candidates.empty())
        throw InvalidInputError("Refiner: the grid has no valid cell");

    std::sort(candidates.begin(), candidates.end(), [](const Candidate& a, const Candidate& b) {
        return a.p.x != b.p.x ? a.p.x < b.p.x : a.p.y < b.p.y;
    });
    // Two cells never share a centre (the geotransform is invertible), except through
    // rounding of a degenerate transform: drop exact repeats.
    candidates.erase(std::unique(candidates.begin(), candidates.end(),
                                 [](const Candidate& a, const Candidate& b) { return a.p == b.p; }),
                     candidates.end());
    std::vector<Candidate> hull(2 * candidates.size() + 1);
    std::size_t k = 0;
    const auto turnsLeft = [&](const Candidate& c) {
        return predicates::orient2d(hull[k - 2].p, hull[k - 1].p, c.p) > 0.0;
    };
    for (const Candidate& c : candidates) {
        while (k >= 2 && !turnsLeft(c))
            --k;
        hull[k++] = c;
    }
    const std::size_t lowerSize = k + 1;
    for (auto it = candidates.rbegin() + 1; it != candidates.rend(); ++it) {
        while (k >= lowerSize && !turnsLeft(*it))
            --k;
        hull[k++] = *it;
    }
    if (k < 4) // the chain closes on its first point: fewer than three corners
        throw InvalidInputError("Refiner: the valid cells are all collinear; a TIN needs area");
    std::vector<std::uint32_t> cells;
    cells.reserve(k - 1);
    for (std::size_t i = 0; i + 1 < k; ++i)
        cells.push_back(hull[i].cell);
    return cells;
}

bool outsideConvexPolygon(std::span<const Point2> corners, Point2 p) {
    const std::size_t n = corners.size();
    const Point2 first = corners[0];
    if (predicates::orient2d(first, corners[1], p) < 0.0 ||
        predicates::orient2d(first, corners[n - 1], p) > 0.0)
        return true; // outside the angle at corners[0]
    // The last corner i in [1, n - 2] with p on the left of, or on, corners[0] -> corners[i]:
    // along the fan the side changes once.
    std::size_t low = 1;
    std::size_t high = n - 2;
    while (low < high) {
        const std::size_t middle = (low + high + 1) / 2;
        if (predicates::orient2d(first, corners[middle], p) >= 0.0)
            low = middle;
        else
            high = middle - 1;
    }
    return predicates::orient2d(corners[low], corners[low + 1], p) < 0.0;
}

} // namespace terratin::detail

#include "projected_sides.hpp"

#include "../refine/error_measure.hpp"

#include "terratin/error.hpp"
#include "terratin/geometry/predicates.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>
#include <utility>

namespace terratin::detail {

namespace {

/// z at cell i on the chord from cell a to cell b, by i's projection onto the chord.
double chordAt(const ProjectedSide& side, std::size_t a, std::size_t b, std::size_t i) {
    const Point2 pa = side.at[a];
    const Point2 pb = side.at[b];
    const Point2 pi = side.at[i];
    const double dx = pb.x - pa.x;
    const double dy = pb.y - pa.y;
    const double t = ((pi.x - pa.x) * dx + (pi.y - pa.y) * dy) / (dx * dx + dy * dy);
    return double{side.z[a]} + (double{side.z[b]} - double{side.z[a]}) * t;
}

/// Whether the valid cells beside the chord from cell a to cell b (columns a to b of each line
/// beside) lie strictly on their own side, and, without a line on one side, whether the side's
/// cells between a and b lie on the chord or inward of it.
bool chordClear(const ProjectedSide& side, std::size_t a, std::size_t b) {
    const Point2 pa = side.at[a];
    const Point2 pb = side.at[b];
    const auto sideOf = [&](Point2 p) {
        const double o = predicates::orient2d(pa, pb, p);
        return o > 0.0 ? side.afterSign : o < 0.0 ? -side.afterSign : 0;
    };
    const auto lineClear = [&](const std::vector<Point2>& line, const std::vector<float>& z,
                               int wanted) {
        for (std::size_t k = a; k <= b; ++k)
            if (!std::isnan(z[k]) && sideOf(line[k]) != wanted)
                return false;
        return true;
    };
    if (!side.after.empty() && !lineClear(side.after, side.afterZ, 1))
        return false;
    if (!side.before.empty() && !lineClear(side.before, side.beforeZ, -1))
        return false;
    for (std::size_t i = a + 1; i < b; ++i) {
        if (std::isnan(side.z[i]))
            continue;
        const int s = sideOf(side.at[i]);
        if ((side.before.empty() && s < 0) || (side.after.empty() && s > 0))
            return false;
    }
    return true;
}

/// Where the chord from a to b must split: its worst cell over the tolerance (the first of
/// equal errors), else its middle cell when it bends too much; a when it needs no split.
std::size_t splitOf(const ProjectedSide& side, std::size_t a, std::size_t b, double tolerance) {
    std::size_t worst = a;
    double worstError = tolerance;
    for (std::size_t i = a + 1; i < b; ++i) {
        const double error = cellError(side.z[i], chordAt(side, a, b, i));
        if (error > worstError) {
            worst = i;
            worstError = error;
        }
    }
    if (worst != a || chordClear(side, a, b))
        return worst;
    if (b == a + 1)
        throw Error("Tiles: the chord between two neighbouring side cells (" + std::to_string(a) +
                    ", " + std::to_string(b) + ") passes a cell beside it");
    return a + (b - a) / 2;
}

/// Whether a cell of the lines beside, next to or across from side cell k, has no data: the
/// tiles' triangles there may cover an open hole, and the cell is kept, so that no cell on a
/// chord is left in such a triangle (a cell on a chord is never inserted).
bool besideNoData(const ProjectedSide& side, std::size_t k) {
    const std::size_t first = k == 0 ? 0 : k - 1;
    const std::size_t last = std::min(k + 1, side.z.size() - 1);
    for (std::size_t i = first; i <= last; ++i)
        if ((!side.beforeZ.empty() && std::isnan(side.beforeZ[i])) ||
            (!side.afterZ.empty() && std::isnan(side.afterZ[i])))
            return true;
    return false;
}

/// Keeps the cells of the valid run [first, last] that the splits need, `first` and `last`
/// excluded. An explicit stack: a staircase profile would recurse once per cell.
void splitRun(const ProjectedSide& side, std::size_t first, std::size_t last, double tolerance,
              std::vector<std::uint32_t>& kept) {
    std::vector<std::pair<std::size_t, std::size_t>> pieces{{first, last}};
    while (!pieces.empty()) {
        const auto [a, b] = pieces.back();
        pieces.pop_back();
        const std::size_t split = splitOf(side, a, b, tolerance);
        if (split == a)
            continue;
        kept.push_back(static_cast<std::uint32_t>(split));
        pieces.emplace_back(a, split);
        pieces.emplace_back(split, b);
    }
}

} // namespace

std::vector<std::uint32_t> keptProjectedSideCells(const ProjectedSide& side,
                                                  std::optional<double> tolerance) {
    std::vector<std::uint32_t> kept;
    std::size_t previousEnd = side.z.size(); // none yet
    std::size_t i = 0;
    while (i < side.z.size()) {
        if (std::isnan(side.z[i])) {
            ++i;
            continue;
        }
        std::size_t last = i;
        while (last + 1 < side.z.size() && !std::isnan(side.z[last + 1]))
            ++last;
        if (previousEnd < side.z.size() && !chordClear(side, previousEnd, i))
            throw InvalidInputError(
                "Refiner: a tile side's " + std::to_string(i - previousEnd - 1) +
                " cells of no data (cells " + std::to_string(previousEnd + 1) + " to " +
                std::to_string(i - 1) +
                ") lie on a line the projection bends past the cells beside it; make the "
                "tiles smaller");
        // The run's ends and its cells beside no data, then what the splits between them need.
        std::size_t from = i;
        kept.push_back(static_cast<std::uint32_t>(i));
        for (std::size_t k = i + 1; k <= last; ++k)
            if (!tolerance || k == last || besideNoData(side, k)) {
                kept.push_back(static_cast<std::uint32_t>(k));
                if (tolerance)
                    splitRun(side, from, k, *tolerance, kept);
                from = k;
            }
        previousEnd = last;
        i = last + 1;
    }
    std::sort(kept.begin(), kept.end());
    return kept;
}

} // namespace terratin::detail

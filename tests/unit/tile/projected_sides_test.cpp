// A tile side's vertices at projected positions (projected_sides.hpp): every valid run's ends,
// the bound along each chord, and chords clear of the cells beside them, checked here by a scan
// of their own on sides bent far more than any projection bends them.

#include "projected_sides.hpp"

#include "terratin/error.hpp"
#include "terratin/geometry/predicates.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <vector>

namespace terratin::detail {
namespace {

constexpr float kNoData = std::numeric_limits<float>::quiet_NaN();

float wavy(std::size_t i) {
    return static_cast<float>(100.0 + 8.0 * std::sin(static_cast<double>(i) * 0.11) +
                              0.7 * static_cast<double>(i % 5));
}

/// A side of `count` cells on an arc of `radius` cells (the lines beside it on the arcs one
/// cell in and out, valid; `outer`: none beyond it, as on the raster's edge), elevations `z(i)`.
ProjectedSide arcSide(std::size_t count, double radius, bool outer,
                      const std::function<float(std::size_t)>& z) {
    ProjectedSide side;
    const auto on = [radius](double line, std::size_t i) {
        const double angle = static_cast<double>(i) / radius;
        return Point2{(radius - line) * std::sin(angle), (radius - line) * std::cos(angle)};
    };
    for (std::size_t i = 0; i < count; ++i) {
        side.z.push_back(z(i));
        side.at.push_back(on(0.0, i));
        side.afterZ.push_back(wavy(i));
        side.after.push_back(on(1.0, i));
        if (!outer) {
            side.beforeZ.push_back(wavy(i));
            side.before.push_back(on(-1.0, i));
        }
    }
    side.afterSign = predicates::orient2d(side.at[0], side.at[1], side.after[0]) > 0.0 ? 1 : -1;
    return side;
}

/// The side of `line` relative to the chord a -> b, as +1 for the after side.
int sideOf(const ProjectedSide& side, std::size_t a, std::size_t b, Point2 p) {
    const double o = predicates::orient2d(side.at[a], side.at[b], p);
    return o > 0.0 ? side.afterSign : o < 0.0 ? -side.afterSign : 0;
}

/// EXPECTs what keptProjectedSideCells promises of `kept`, by a scan of its own.
void expectKeptSide(const ProjectedSide& side, const std::vector<std::uint32_t>& kept,
                    double tolerance) {
    for (std::size_t i = 0; i < side.z.size(); ++i) {
        const bool runEnd =
            !std::isnan(side.z[i]) && (i == 0 || std::isnan(side.z[i - 1]) ||
                                       i + 1 == side.z.size() || std::isnan(side.z[i + 1]));
        if (runEnd) {
            EXPECT_NE(std::find(kept.begin(), kept.end(), i), kept.end()) << "run end " << i;
        }
    }
    for (std::size_t k = 0; k + 1 < kept.size(); ++k) {
        const std::size_t a = kept[k];
        const std::size_t b = kept[k + 1];
        for (std::size_t i = a; i <= b; ++i) {
            if (!side.after.empty() && !std::isnan(side.afterZ[i])) {
                EXPECT_EQ(sideOf(side, a, b, side.after[i]), 1) << "chord " << a << "-" << b;
            }
            if (!side.before.empty() && !std::isnan(side.beforeZ[i])) {
                EXPECT_EQ(sideOf(side, a, b, side.before[i]), -1) << "chord " << a << "-" << b;
            }
            if (i == a || i == b || std::isnan(side.z[i]))
                continue;
            if (side.before.empty()) {
                EXPECT_GE(sideOf(side, a, b, side.at[i]), 0) << "cell " << i << " beyond";
            }
            const double dx = side.at[b].x - side.at[a].x;
            const double dy = side.at[b].y - side.at[a].y;
            const double t =
                ((side.at[i].x - side.at[a].x) * dx + (side.at[i].y - side.at[a].y) * dy) /
                (dx * dx + dy * dy);
            const double line = side.z[a] + (side.z[b] - side.z[a]) * t;
            EXPECT_LE(std::abs(side.z[i] - line), tolerance) << "cell " << i;
        }
    }
}

TEST(ProjectedSides, AStraightEvenSide_KeepsItsRunsEndsWhereTheProfileIsStraight) {
    ProjectedSide side;
    for (std::size_t i = 0; i < 50; ++i) {
        side.z.push_back(i >= 20 && i < 25 ? kNoData : static_cast<float>(2 * i));
        side.at.push_back({static_cast<double>(i), 0.0});
        side.afterZ.push_back(1.0F);
        side.after.push_back({static_cast<double>(i), 1.0});
    }
    side.afterSign = 1;
    EXPECT_EQ(keptProjectedSideCells(side, 0.1), (std::vector<std::uint32_t>{0, 19, 25, 49}));
    // Full resolution: every valid cell.
    EXPECT_EQ(keptProjectedSideCells(side, std::nullopt).size(), 45U);
}

TEST(ProjectedSides, ABentSide_ChordsClearOfTheLinesBeside_AndWithinTheTolerance) {
    for (const double radius : {40.0, -40.0, 400.0}) { // bent either way
        SCOPED_TRACE("radius " + std::to_string(radius));
        const ProjectedSide side = arcSide(150, radius, false, wavy);
        const std::vector<std::uint32_t> kept = keptProjectedSideCells(side, 1.0);
        expectKeptSide(side, kept, 1.0);
        // A loose tolerance still splits where the arc bends past the lines beside.
        const std::vector<std::uint32_t> loose = keptProjectedSideCells(side, 1000.0);
        expectKeptSide(side, loose, 1000.0);
        if (std::abs(radius) < 100.0) {
            EXPECT_GT(loose.size(), 4U);
        }
    }
}

TEST(ProjectedSides, AnOuterSide_LeavesNoCellBeyondItsChords) {
    for (const double radius : {40.0, -40.0}) {
        SCOPED_TRACE("radius " + std::to_string(radius));
        const ProjectedSide side = arcSide(120, radius, true, wavy);
        expectKeptSide(side, keptProjectedSideCells(side, 1000.0), 1000.0);
    }
}

TEST(ProjectedSides, AGapTheProjectionBendsPastACellBeside_IsRefused) {
    // 60 cells of no data on an arc of 40 cells' radius: the chord across them passes more than
    // ten cells inside the arc, beyond the valid line beside it.
    const auto gap = [](std::size_t i) { return i >= 10 && i < 70 ? kNoData : wavy(i); };
    const ProjectedSide bent = arcSide(80, 40.0, false, gap);
    EXPECT_THROW(keptProjectedSideCells(bent, 1.0), InvalidInputError);
    EXPECT_THROW(keptProjectedSideCells(bent, std::nullopt), InvalidInputError);
    // Where the lines beside have no data there either, nothing stands in the chord's way.
    ProjectedSide open = bent;
    for (std::size_t i = 10; i < 70; ++i) {
        open.afterZ[i] = kNoData;
        open.beforeZ[i] = kNoData;
    }
    expectKeptSide(open, keptProjectedSideCells(open, 1.0), 1.0);
}

} // namespace
} // namespace terratin::detail

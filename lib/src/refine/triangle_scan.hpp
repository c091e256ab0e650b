#pragma once
/// @file
/// The refiner's measurement of one triangle: its farthest valid cell from the triangle's
/// plane, in two steps so that the memory requests of several triangles overlap.
///
/// A triangle's rows lie a raster row apart, so each row is a cache miss (two: elevations and
/// flags). prepare() finds the rows' intervals and requests their cells; measure() reads them.
/// The refiner prepares all triangles around a new vertex before measuring the first, so
/// their misses are served together instead of one triangle after the other. A triangle of
/// more than kPreparedRows rows (early in a refinement) is measured in batches instead.

#include "grid_scan.hpp"

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <optional>

namespace terratin::detail {

struct ScanResult {
    /// The largest error over the valid non-vertex cells, -1 when there is none.
    double best = -1.0;
    /// Its cell (the lowest such cell index on ties).
    std::int64_t bestCell = 0;
    /// Whether the triangle covers a cell of an open hole.
    bool coversHole = false;
};

/// Measures the cells of row `row`, columns lo..hi, of `triangle` into `result`.
inline void measureSpan(const GridView& view, const PixelTriangle& triangle, std::int64_t row,
                        std::int64_t lo, std::int64_t hi, ScanResult& result) {
    const float* z = view.z + row * view.width;
    const std::uint8_t* flags = view.flags + row * view.width;
    const double base = triangle.rowBase(row);
    const double gradCol = triangle.gradCol();
    for (std::int64_t col = lo; col <= hi; ++col) {
        if (flags[col] != 0) {
            result.coversHole |= (flags[col] & kCellOpenHole) != 0;
            continue;
        }
        const double error =
            std::fabs(static_cast<double>(z[col]) - (base + gradCol * static_cast<double>(col)));
        if (error > result.best) {
            result.best = error;
            result.bestCell = row * view.width + col;
        }
    }
}

/// Measures the rows rowFrom..rowTo of a triangle, a part of a large one (requires hasArea()).
inline ScanResult measureRows(const PixelTriangle& triangle, const GridView& view,
                              std::int64_t rowFrom, std::int64_t rowTo) {
    ScanResult result;
    triangle.forEachRow(
        view.width, view.height, nullptr,
        [&](std::int64_t row, std::int64_t lo, std::int64_t hi) {
            measureSpan(view, triangle, row, lo, hi, result);
        },
        rowFrom, rowTo);
    return result;
}

/// Adds the measure of a later part of the same triangle (rows after total's): the result is
/// the one of measuring both parts at once.
inline void mergeLater(ScanResult& total, const ScanResult& later) {
    // A later part's cells have higher indices: it wins a tie only against nothing.
    if (later.best > total.best) {
        total.best = later.best;
        total.bestCell = later.bestCell;
    }
    total.coversHole |= later.coversHole;
}

class TriangleScan {
public:
    static constexpr std::size_t kPreparedRows = 32;

    /// Returns false when the triangle has no cell to measure: no pixel area (its cells lie on
    /// the neighbours' edges, see grid_scan.hpp) or nothing but its corners, which are
    /// vertices.
    bool prepare(const PixelTriangle& triangle, const GridView& view) {
        m_triangle.reset();
        if (!triangle.hasArea() || triangle.coversOnlyCorners())
            return false;
        m_triangle.emplace(triangle);
        m_count = 0;
        m_complete = true;
        triangle.forEachRow(view.width, view.height, nullptr,
                            [&](std::int64_t row, std::int64_t lo, std::int64_t hi) {
                                if (m_count == m_spans.size()) {
                                    m_complete = false;
                                    return;
                                }
                                request(view, row, lo);
                                m_spans[m_count++] = {row, lo, hi};
                            });
        return true;
    }

    /// Measures the prepared triangle; requires prepare() to have returned true.
    [[nodiscard]] ScanResult measure(const GridView& view) const {
        ScanResult result;
        if (m_complete) {
            for (std::size_t i = 0; i < m_count; ++i)
                measureRow(view, m_spans[i], result);
            return result;
        }
        // Too many rows to keep: walk them again, requesting a batch before measuring it.
        std::array<Span, kPreparedRows> batch;
        std::size_t count = 0;
        m_triangle->forEachRow(view.width, view.height, nullptr,
                               [&](std::int64_t row, std::int64_t lo, std::int64_t hi) {
                                   request(view, row, lo);
                                   batch[count++] = {row, lo, hi};
                                   if (count == batch.size()) {
                                       for (const Span& span : batch)
                                           measureRow(view, span, result);
                                       count = 0;
                                   }
                               });
        for (std::size_t i = 0; i < count; ++i)
            measureRow(view, batch[i], result);
        return result;
    }

private:
    /// One row of the triangle's cells: columns lo..hi.
    struct Span {
        std::int64_t row;
        std::int64_t lo;
        std::int64_t hi;
    };

    static void request(const GridView& view, std::int64_t row, std::int64_t lo) {
        __builtin_prefetch(view.z + row * view.width + lo);
        __builtin_prefetch(view.flags + row * view.width + lo);
    }

    void measureRow(const GridView& view, const Span& span, ScanResult& result) const {
        measureSpan(view, *m_triangle, span.row, span.lo, span.hi, result);
    }

    std::optional<PixelTriangle> m_triangle;
    std::array<Span, kPreparedRows> m_spans; // [0, m_count) set by prepare()
    std::size_t m_count = 0;
    bool m_complete = true;
};

} // namespace terratin::detail

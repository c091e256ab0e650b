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
#include "span_measure.hpp"

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <optional>

namespace terratin::detail {

/// Measures the rows rowFrom..rowTo of a triangle, a part of a large one (requires hasArea()).
inline ScanResult measureRows(const PixelTriangle& triangle, const GridView& view,
                              std::int64_t rowFrom, std::int64_t rowTo) {
    ScanResult result;
    triangle.forEachRow(
        view.width, view.height, nullptr,
        [&](std::int64_t row, std::int64_t lo, std::int64_t hi) {
            const RowSpan span{row, lo, hi};
            measureSpans(view, triangle, &span, 1, result);
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
    bool prepare(const PixelCorner& a, const PixelCorner& b, const PixelCorner& c,
                 const GridView& view) {
        // Built in place: a copy of a just-built triangle stalls on store forwarding.
        const PixelTriangle& triangle = m_triangle.emplace(a, b, c);
        if (!triangle.hasArea() || triangle.coversOnlyCorners())
            return false;
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
            measureSpans(view, *m_triangle, m_spans.data(), m_count, result);
            return result;
        }
        // Too many rows to keep: walk them again, requesting a batch before measuring it.
        std::array<RowSpan, kPreparedRows> batch;
        std::size_t count = 0;
        m_triangle->forEachRow(view.width, view.height, nullptr,
                               [&](std::int64_t row, std::int64_t lo, std::int64_t hi) {
                                   request(view, row, lo);
                                   batch[count++] = {row, lo, hi};
                                   if (count == batch.size()) {
                                       measureSpans(view, *m_triangle, batch.data(), count, result);
                                       count = 0;
                                   }
                               });
        measureSpans(view, *m_triangle, batch.data(), count, result);
        return result;
    }

private:
    static void request(const GridView& view, std::int64_t row, std::int64_t lo) {
        __builtin_prefetch(view.z + row * view.width + lo);
        __builtin_prefetch(view.flags + row * view.width + lo);
    }

    std::optional<PixelTriangle> m_triangle;
    std::array<RowSpan, kPreparedRows> m_spans; // [0, m_count) set by prepare()
    std::size_t m_count = 0;
    bool m_complete = true;
};

} // namespace terratin::detail

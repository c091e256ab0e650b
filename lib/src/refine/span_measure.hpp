#pragma once
/// @file
/// The refiner's innermost loop: the largest error over a triangle's rows of cells.
///
/// A fine refinement measures about 50 million cells in 1.5 million triangles, and the loop
/// is bound by arithmetic, not memory. Where the processor has AVX2 (checked once, at run
/// time), four cells are measured at once; elsewhere one at a time. Both evaluate the plane
/// with the same operations in the same order (no fused multiply-add), so they give
/// bit-identical errors and pick the same cell.

#include "error_measure.hpp"
#include "grid_scan.hpp"

#include <cmath>
#include <cstddef>
#include <cstdint>

namespace terratin::detail {

struct ScanResult {
    /// The largest error over the valid non-vertex cells, -1 when there is none.
    double best = -1.0;
    /// Its cell (the lowest such cell index on ties).
    std::int64_t bestCell = 0;
    /// Whether the triangle covers a cell of an open hole.
    bool coversHole = false;
};

/// One row of a triangle's cells: columns lo..hi. No initialisers: the scans keep arrays of
/// them on the stack, written before they are read, and zeroing those cost a measurable share
/// of a refinement (docs/benchmarks.md).
struct RowSpan {
    std::int64_t row;
    std::int64_t lo;
    std::int64_t hi;
};

/// Measures the cells of row `row`, columns lo..hi, of `triangle` into `result`, one at a time.
inline void measureSpan(const GridView& view, const PixelTriangle& triangle, std::int64_t row,
                        std::int64_t lo, std::int64_t hi, ScanResult& result) {
    const float* z = view.z + row * view.width;
    const std::uint8_t* flags = view.flags + row * view.width;
    const double base = triangle.rowBase(row);
    const double gradCol = triangle.gradCol();
    // In locals: `result` might alias the flags (bytes alias anything), which would keep it
    // in memory.
    double best = result.best;
    std::int64_t bestCol = -1;
    std::uint8_t seen = 0;
    for (std::int64_t col = lo; col <= hi; ++col) {
        seen |= flags[col];
        if (flags[col] != 0)
            continue;
        const double error = cellError(z[col], base + gradCol * static_cast<double>(col));
        if (error > best) {
            best = error;
            bestCol = col;
        }
    }
    if (bestCol >= 0) {
        result.best = best;
        result.bestCell = row * view.width + bestCol;
    }
    result.coversHole |= (seen & kCellOpenHole) != 0;
}

/// measureSpan on each of `count` spans in order (rows increasing), four cells at a time where
/// the processor allows it.
void measureSpans(const GridView& view, const PixelTriangle& triangle, const RowSpan* spans,
                  std::size_t count, ScanResult& result);

/// Whether measureSpans runs four cells at a time on this processor.
[[nodiscard]] bool measuresFourCellsAtOnce();

/// measureSpans as it runs on a processor without AVX2 (for the tests).
void measureSpansOneByOne(const GridView& view, const PixelTriangle& triangle, const RowSpan* spans,
                          std::size_t count, ScanResult& result);

} // namespace terratin::detail

#include "span_measure.hpp"

#include <algorithm>
#include <cstring>

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#define TERRATIN_MEASURE_AVX2 1
#include <immintrin.h>
#endif

namespace terratin::detail {

void measureSpansOneByOne(const GridView& view, const PixelTriangle& triangle, const RowSpan* spans,
                          std::size_t count, ScanResult& result) {
    for (std::size_t i = 0; i < count; ++i)
        measureSpan(view, triangle, spans[i].row, spans[i].lo, spans[i].hi, result);
}

#if defined(TERRATIN_MEASURE_AVX2)

namespace {

/// Four lanes of cells. Each lane keeps its own largest error and cell, updated only when
/// strictly larger, so within a lane the lowest cell wins a tie, as in measureSpan; the
/// reduction at the end takes the largest error and, among equal ones, the lowest cell.
struct FourLanes {
    __m256d best;
    __m256d cell; // cell indices are integers under 2^53: exact in a double
    std::uint32_t flagsSeen = 0;
};

/// Measures four cells: their elevations, flags (lane i in byte i), columns and indices.
__attribute__((target("avx2"))) inline void measureFour(FourLanes& lanes, __m128 z,
                                                        std::uint32_t flags, __m256d columns,
                                                        __m256d base, __m256d gradCol,
                                                        __m256d cells) {
    const __m256d absolute = _mm256_castsi256_pd(_mm256_set1_epi64x(0x7fffffffffffffff));
    const __m256d elevation = _mm256_cvtps_pd(z);
    // The plane as measureSpan evaluates it: base + gradCol * col, then cellError's |z - plane|.
    const __m256d plane = _mm256_add_pd(base, _mm256_mul_pd(gradCol, columns));
    const __m256d error = _mm256_and_pd(_mm256_sub_pd(elevation, plane), absolute);
    const __m256i laneFlags = _mm256_cvtepu8_epi64(_mm_cvtsi32_si128(static_cast<int>(flags)));
    const __m256d measured =
        _mm256_castsi256_pd(_mm256_cmpeq_epi64(laneFlags, _mm256_setzero_si256()));
    // A cell with a flag (no data, a vertex) has no error: -1, never above a lane's best.
    const __m256d candidate = _mm256_blendv_pd(_mm256_set1_pd(-1.0), error, measured);
    // The maximum, not a blend, carries the lanes' best from one group to the next: a
    // shorter chain of dependent instructions.
    const __m256d larger = _mm256_cmp_pd(candidate, lanes.best, _CMP_GT_OQ);
    lanes.best = _mm256_max_pd(lanes.best, candidate);
    lanes.cell = _mm256_blendv_pd(lanes.cell, cells, larger);
    lanes.flagsSeen |= flags;
}

__attribute__((target("avx2"))) void measureSpansFourAtOnce(const GridView& view,
                                                            const PixelTriangle& triangle,
                                                            const RowSpan* spans, std::size_t count,
                                                            ScanResult& result) {
    const __m256d gradCol = _mm256_set1_pd(triangle.gradCol());
    const __m256d laneOffsets = _mm256_setr_pd(0.0, 1.0, 2.0, 3.0);
    const __m256d four = _mm256_set1_pd(4.0);
    FourLanes lanes{_mm256_set1_pd(-1.0), _mm256_setzero_pd()};
    for (std::size_t i = 0; i < count; ++i) {
        const RowSpan& span = spans[i];
        const std::int64_t rowStart = span.row * view.width;
        const float* z = view.z + rowStart;
        const std::uint8_t* flags = view.flags + rowStart;
        const __m256d base = _mm256_set1_pd(triangle.rowBase(span.row));
        __m256d columns = _mm256_add_pd(_mm256_set1_pd(static_cast<double>(span.lo)), laneOffsets);
        __m256d cells =
            _mm256_add_pd(_mm256_set1_pd(static_cast<double>(rowStart + span.lo)), laneOffsets);
        std::int64_t col = span.lo;
        for (; col + 3 <= span.hi; col += 4) {
            std::uint32_t fourFlags = 0;
            std::memcpy(&fourFlags, flags + col, sizeof fourFlags);
            measureFour(lanes, _mm_loadu_ps(z + col), fourFlags, columns, base, gradCol, cells);
            columns = _mm256_add_pd(columns, four);
            cells = _mm256_add_pd(cells, four);
        }
        if (col > span.hi)
            continue;
        // The last one to three cells; the lanes past the span get kCellNoData. Nothing past
        // the span is read: the flags there may be another strip's, being written. (Built in
        // registers: a lane-by-lane copy read back whole would stall on store forwarding.)
        const auto used = static_cast<int>(span.hi - col + 1);
        const __m128 tailZ = _mm_maskload_ps(
            z + col, _mm_cmpgt_epi32(_mm_set1_epi32(used), _mm_setr_epi32(0, 1, 2, 3)));
        // Branch-free (the length is unpredictable): lanes past the span read its last cell.
        const auto flagAt = [&](std::int64_t lane) {
            return static_cast<std::uint32_t>(flags[std::min(col + lane, span.hi)]) << (8 * lane);
        };
        const std::uint32_t read = flagAt(0) | flagAt(1) | flagAt(2);
        const std::uint32_t keep = (std::uint32_t{1} << (8 * used)) - 1U;
        const std::uint32_t padding = 0x01010101U * kCellNoData;
        measureFour(lanes, tailZ, (read & keep) | (padding & ~keep), columns, base, gradCol, cells);
    }
    alignas(32) double best[4];
    alignas(32) double cell[4];
    _mm256_store_pd(best, lanes.best);
    _mm256_store_pd(cell, lanes.cell);
    for (int lane = 0; lane < 4; ++lane) {
        const auto laneCell = static_cast<std::int64_t>(cell[lane]);
        if (best[lane] > result.best ||
            (best[lane] == result.best && best[lane] >= 0.0 && laneCell < result.bestCell)) {
            result.best = best[lane];
            result.bestCell = laneCell;
        }
    }
    result.coversHole |= (lanes.flagsSeen & (0x01010101U * kCellOpenHole)) != 0;
}

bool detectAvx2() {
    __builtin_cpu_init();
    return __builtin_cpu_supports("avx2") != 0;
}

} // namespace

bool measuresFourCellsAtOnce() {
    static const bool hasAvx2 = detectAvx2();
    return hasAvx2;
}

void measureSpans(const GridView& view, const PixelTriangle& triangle, const RowSpan* spans,
                  std::size_t count, ScanResult& result) {
    if (measuresFourCellsAtOnce())
        measureSpansFourAtOnce(view, triangle, spans, count, result);
    else
        measureSpansOneByOne(view, triangle, spans, count, result);
}

#else

bool measuresFourCellsAtOnce() {
    return false;
}

void measureSpans(const GridView& view, const PixelTriangle& triangle, const RowSpan* spans,
                  std::size_t count, ScanResult& result) {
    measureSpansOneByOne(view, triangle, spans, count, result);
}

#endif

} // namespace terratin::detail

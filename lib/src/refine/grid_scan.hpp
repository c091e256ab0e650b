#pragma once
/// @file
/// Visiting the cells whose centres lie in a triangle of cell centres, in pixel coordinates.
///
/// Notation: a cell centre is the integer point (col, row); a triangle's corners are cells
/// a, b, c. In pixel space every decision is exact integer arithmetic: for each row the
/// cells inside form one interval [lo, hi], the intersection of the three edges' half-planes.
/// The TIN itself is built in CRS coordinates with exact predicates; the geotransform is
/// affine, so a triangle with a nonzero pixel orientation keeps its orientation sign in CRS
/// coordinates (rounding moves a centre by ~1e-16 of its coordinate, far less than a lattice
/// triangle's area of at least half a cell). Only pixel-collinear corners (a zero-area pixel
/// triangle, a CRS sliver on a rounded diagonal) are special: they interpolate nothing, and
/// their cells lie on the edges of the neighbouring triangles, which scan them.
///
/// Cost: for a small triangle, a few vector operations per row (forEachRowByMasks); for a
/// larger one, one integer division per edge, then a carried remainder per edge per row.

#include "terratin/geometry/height_grid.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <utility>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace terratin::detail {

/// Per-cell flags beside the grid: one byte per cell.
enum CellFlag : std::uint8_t {
    kCellNoData = 1,   ///< no elevation: never a vertex, never measured
    kCellVertex = 2,   ///< already a vertex of the TIN (its error is 0)
    kCellOpenHole = 4, ///< nodata cell of a hole larger than maxHole: no triangle may cover it
    kCellFrozen = 8    ///< a tile's border cell: never a candidate (tile_refine.hpp decides them)
};

/// Read-only view of what the scans need.
struct GridView {
    std::int64_t width = 0;
    std::int64_t height = 0;
    const float* z = nullptr;
    const std::uint8_t* flags = nullptr;
};

/// A corner of a triangle: the cell's pixel coordinates and elevation.
struct PixelCorner {
    std::int64_t col = 0;
    std::int64_t row = 0;
    double z = 0.0;
    /// The caller's name for the corner (a vertex id), carried through the reordering.
    std::uint32_t id = 0;
};

inline std::int64_t floorDiv(std::int64_t a, std::int64_t b) {
    std::int64_t q = a / b;
    if ((a % b != 0) && ((a < 0) != (b < 0)))
        --q;
    return q;
}
inline std::int64_t ceilDiv(std::int64_t a, std::int64_t b) {
    return -floorDiv(-a, b);
}

/// floorDiv for b > 0, through a double division where that is exact: with |a| < 2^53 the
/// rounded quotient of a non-integer a / b stays more than 1 / b from the next integer, so
/// its integer part is the exact one. A divsd pipelines; the 64-bit idiv it replaces does not, and
/// a scan starts with six of them.
inline std::int64_t floorDivPositive(std::int64_t a, std::int64_t b) {
    constexpr std::int64_t kExactBound = std::int64_t{1} << 52;
    if (a <= -kExactBound || a >= kExactBound || b >= kExactBound)
        return floorDiv(a, b);
    // Truncation, then the exact integer correction of a negative non-integer quotient
    // (std::floor would be a libm call without SSE4.1).
    auto q = static_cast<std::int64_t>(static_cast<double>(a) / static_cast<double>(b));
    if (q * b > a)
        --q;
    return q;
}

/// One edge's constraint on the columns of successive rows (PixelTriangle::forEachRowPair):
/// N(r) = n0 + (r - first) * step; with slope > 0 the row's cells satisfy x >= -floor(N /
/// slope), with slope < 0 x <= floor(N / -slope), with slope 0 all or none (N >= 0).
class EdgeWalk {
public:
    void start(std::int64_t slope, std::int64_t n0, std::int64_t step) {
        m_slope = slope;
        if (slope == 0) {
            m_quotient = n0;
            m_stepQuotient = step;
            return;
        }
        m_divisor = slope > 0 ? slope : -slope;
        m_quotient = floorDivPositive(n0, m_divisor);
        m_remainder = n0 - m_quotient * m_divisor;
        m_stepQuotient = floorDivPositive(step, m_divisor);
        m_stepRemainder = step - m_stepQuotient * m_divisor;
    }
    void clip(std::int64_t& lo, std::int64_t& hi) const {
        if (m_slope > 0)
            lo = std::max(lo, -m_quotient);
        else if (m_slope < 0)
            hi = std::min(hi, m_quotient);
        else if (m_quotient < 0)
            hi = -1; // the row lies beyond this horizontal edge
    }
    void advance() {
        m_quotient += m_stepQuotient;
        if (m_slope == 0)
            return;
        m_remainder += m_stepRemainder;
        if (m_remainder >= m_divisor) {
            m_remainder -= m_divisor;
            ++m_quotient;
        }
    }

private:
    std::int64_t m_slope = 0;
    std::int64_t m_divisor = 1;
    /// floor(N / divisor) (N itself for a horizontal edge) and N - quotient * divisor.
    std::int64_t m_quotient = 0;
    std::int64_t m_remainder = 0;
    std::int64_t m_stepQuotient = 0;
    std::int64_t m_stepRemainder = 0;
};

/// A triangle of cell centres prepared for row-by-row visits and linear interpolation.
class PixelTriangle {
public:
    /// Corners in any order. The corner with the smallest cell index becomes the base of the
    /// interpolation, so that the same triangle always gives bit-identical values. Always
    /// inlined: called, it received its corners through the stack, written field by field
    /// and read back wider, a store-forwarding stall that cost a measurable share of a
    /// refinement (docs/benchmarks.md).
    [[gnu::always_inline]] PixelTriangle(PixelCorner a, PixelCorner b, PixelCorner c) {
        const auto key = [](const PixelCorner& p) { return std::pair(p.row, p.col); };
        if (key(b) < key(a))
            std::swap(a, b);
        if (key(c) < key(a))
            std::swap(a, c);
        m_corner = {a, b, c};
        const std::int64_t bc = b.col - a.col;
        const std::int64_t br = b.row - a.row;
        const std::int64_t cc = c.col - a.col;
        const std::int64_t cr = c.row - a.row;
        m_det = bc * cr - cc * br;
        if (m_det != 0) {
            const double det = static_cast<double>(m_det);
            const double dzb = b.z - a.z;
            const double dzc = c.z - a.z;
            m_gradCol = (dzb * static_cast<double>(cr) - dzc * static_cast<double>(br)) / det;
            m_gradRow = (dzc * static_cast<double>(bc) - dzb * static_cast<double>(cc)) / det;
        }
        m_rowMin = std::min({a.row, b.row, c.row});
        m_rowMax = std::max({a.row, b.row, c.row});
    }

    /// False for pixel-collinear corners (zero pixel area).
    [[nodiscard]] bool hasArea() const { return m_det != 0; }
    /// True when the closed triangle holds no cell but its corners: by Pick's theorem a
    /// lattice triangle of area 1/2 has no lattice point inside or on its edges besides its
    /// corners. A quarter of the triangles a fine refinement scans are such.
    [[nodiscard]] bool coversOnlyCorners() const { return m_det == 1 || m_det == -1; }
    [[nodiscard]] const PixelCorner& corner(int i) const {
        return m_corner[static_cast<std::size_t>(i)];
    }

    /// Elevation of the plane through the corners at (col, row), for the row base given by
    /// rowBase(row): rowBase + gradCol * col.
    [[nodiscard]] double rowBase(std::int64_t row) const {
        const PixelCorner& a = m_corner[0];
        return a.z + m_gradRow * static_cast<double>(row - a.row) -
               m_gradCol * static_cast<double>(a.col);
    }
    [[nodiscard]] double gradCol() const { return m_gradCol; }

    /// Twice the triangle's area in cells (about twice the cells it covers).
    [[nodiscard]] std::int64_t doubleArea() const { return m_det < 0 ? -m_det : m_det; }
    [[nodiscard]] std::int64_t rowMin() const { return m_rowMin; }
    [[nodiscard]] std::int64_t rowMax() const { return m_rowMax; }

    /// Calls visit(row, lo, hi) for each row of the grid with cells inside the closed
    /// triangle, [lo, hi] the inclusive column interval, clipped to the grid and to the rows
    /// rowFrom..rowTo. When `strictEdge` is given, the cells on edge i (corner(i) to
    /// corner(i+1)) are left out where strictEdge[i] is true (see ownsSharedEdge), and rows
    /// left empty are skipped. Requires hasArea().
    template <class Visit>
    void forEachRow(std::int64_t gridWidth, std::int64_t gridHeight, const bool* strictEdge,
                    Visit&& visit, std::int64_t rowFrom = 0,
                    std::int64_t rowTo = std::numeric_limits<std::int64_t>::max()) const {
        // Edge i runs from corner i to corner i+1; a cell (x, r) is inside when
        // sgn * orient(p, q, (x, r)) >= t (t = 0 closed, 1 to leave the edge's cells out), with
        //   orient(p, q, (x, r)) = (q.col - p.col)(r - p.row) - (q.row - p.row)(x - p.col).
        // As a condition on x: slope * x >= bound(r), slope = -sgn (q.row - p.row), where
        // bound(r) = t - sgn * ((q.col - p.col)(r - p.row) + (q.row - p.row) p.col) changes by
        // a constant from row to row. Writing N(r) = -bound(r): slope > 0 gives x >= -floor(N /
        // slope), slope < 0 gives x <= floor(N / -slope), slope == 0 needs N(r) >= 0. The floor
        // divisions are carried from row to row with a remainder (Bresenham), exactly.
        const std::int64_t sgn = m_det > 0 ? 1 : -1;
        const std::int64_t rowFirst = std::max({m_rowMin, rowFrom, std::int64_t{0}});
        const std::int64_t rowLast = std::min({m_rowMax, rowTo, gridHeight - 1});
        if (rowFirst > rowLast)
            return;
        if (forEachRowByMasks(gridWidth, rowFirst, rowLast, strictEdge, visit))
            return;
        EdgeWalk edges[3];
        for (int i = 0; i < 3; ++i) {
            const PixelCorner& p = m_corner[static_cast<std::size_t>(i)];
            const PixelCorner& q = m_corner[static_cast<std::size_t>((i + 1) % 3)];
            const std::int64_t slope = -sgn * (q.row - p.row);
            const std::int64_t k = (q.col - p.col) * (rowFirst - p.row) + (q.row - p.row) * p.col;
            const std::int64_t t = strictEdge != nullptr && strictEdge[i] ? 1 : 0;
            edges[i].start(slope, sgn * k - t, sgn * (q.col - p.col));
        }
        for (std::int64_t r = rowFirst; r <= rowLast; ++r) {
            std::int64_t lo = 0;
            std::int64_t hi = gridWidth - 1;
            for (const EdgeWalk& edge : edges)
                edge.clip(lo, hi);
            if (lo <= hi)
                visit(r, lo, hi);
            for (EdgeWalk& edge : edges)
                edge.advance();
        }
    }

    /// Calls visit(col, row) for every lattice point on the segment of a triangle without
    /// pixel area (from its two extreme corners), clipped to nothing: the corners are cells.
    template <class Visit> void forEachOnSegment(Visit&& visit) const {
        PixelCorner from = m_corner[0];
        PixelCorner to = m_corner[0];
        const auto key = [](const PixelCorner& p) { return std::pair(p.row, p.col); };
        for (const PixelCorner& p : m_corner) {
            if (key(p) < key(from))
                from = p;
            if (key(to) < key(p))
                to = p;
        }
        const std::int64_t dc = to.col - from.col;
        const std::int64_t dr = to.row - from.row;
        const std::int64_t steps = std::gcd(dc < 0 ? -dc : dc, dr);
        if (steps == 0) {
            visit(from.col, from.row);
            return;
        }
        for (std::int64_t s = 0; s <= steps; ++s)
            visit(from.col + dc / steps * s, from.row + dr / steps * s);
    }

    /// Whether this triangle owns the cells on its edge i (corner i to corner i+1) when a
    /// neighbour shares it. Two triangles on either side of an edge traverse it in opposite
    /// directions when both are taken counter-clockwise in pixel space; the one for which it
    /// runs row-increasing (or column-increasing along a row) owns it. Requires hasArea().
    [[nodiscard]] bool ownsSharedEdge(int i) const {
        const PixelCorner& p = m_corner[static_cast<std::size_t>(i)];
        const PixelCorner& q = m_corner[static_cast<std::size_t>((i + 1) % 3)];
        const bool increasing = q.row > p.row || (q.row == p.row && q.col > p.col);
        return increasing == (m_det > 0);
    }

private:
#if defined(__SSE2__)
    /// An edge's function sgn * orient(p, q, (x, r)) - t (forEachRow) at the 16 columns from a
    /// triangle's first one, in 16-bit lanes: columns 0..7 and 8..15 of the current row, and
    /// the change from one row to the next.
    struct EdgeLanes {
        __m128i first;
        __m128i last;
        __m128i rowStep;
        void nextRow() {
            first = _mm_add_epi16(first, rowStep);
            last = _mm_add_epi16(last, rowStep);
        }
    };
    /// Edge i's lanes at row `row` from column `colMin`; `strict` leaves its cells out.
    [[nodiscard]] EdgeLanes edgeLanes(std::size_t i, std::int64_t row, std::int64_t colMin,
                                      bool strict) const {
        const std::int64_t sgn = m_det > 0 ? 1 : -1;
        const PixelCorner& p = m_corner[i];
        const PixelCorner& q = m_corner[(i + 1) % 3];
        const std::int64_t perColumn = -sgn * (q.row - p.row);
        const std::int64_t perRow = sgn * (q.col - p.col);
        const std::int64_t t = strict ? 1 : 0;
        const std::int64_t start = perRow * (row - p.row) + perColumn * (colMin - p.col) - t;
        const __m128i column = _mm_set1_epi16(static_cast<short>(perColumn));
        const __m128i base = _mm_set1_epi16(static_cast<short>(start));
        return {
            _mm_add_epi16(base, _mm_mullo_epi16(column, _mm_setr_epi16(0, 1, 2, 3, 4, 5, 6, 7))),
            _mm_add_epi16(base,
                          _mm_mullo_epi16(column, _mm_setr_epi16(8, 9, 10, 11, 12, 13, 14, 15))),
            _mm_set1_epi16(static_cast<short>(perRow))};
    }
#endif

    /// forEachRow's visits, for a triangle of at most 16 columns and 32 rows (97% of those a
    /// refinement scans): the edge functions sgn * orient(p, q, (x, r)) - t of 16
    /// columns at once, in 16-bit lanes (exact: they stay under 2^11 in magnitude), give each
    /// row's cells as a bit mask, with no division and no branch per edge. Returns false,
    /// having visited nothing, for a larger triangle, one reaching past the grid's columns,
    /// or without SSE2.
    template <class Visit>
    bool forEachRowByMasks(std::int64_t gridWidth, std::int64_t rowFirst, std::int64_t rowLast,
                           const bool* strictEdge, Visit& visit) const {
#if defined(__SSE2__)
        constexpr std::int64_t kColumns = 16;
        constexpr std::int64_t kRows = 32;
        const std::int64_t colMin = std::min({m_corner[0].col, m_corner[1].col, m_corner[2].col});
        const std::int64_t colMax = std::max({m_corner[0].col, m_corner[1].col, m_corner[2].col});
        if (colMax - colMin >= kColumns || m_rowMax - m_rowMin >= kRows || colMin < 0 ||
            colMax >= gridWidth)
            return false;
        EdgeLanes edges[3];
        for (std::size_t i = 0; i < 3; ++i)
            edges[i] = edgeLanes(i, rowFirst, colMin, strictEdge != nullptr && strictEdge[i]);
        const unsigned columns = (1U << static_cast<unsigned>(colMax - colMin + 1)) - 1U;
        for (std::int64_t r = rowFirst; r <= rowLast; ++r) {
            // A lane is outside when any edge function is negative: the sign bits of the OR.
            const __m128i firstOr =
                _mm_or_si128(_mm_or_si128(edges[0].first, edges[1].first), edges[2].first);
            const __m128i lastOr =
                _mm_or_si128(_mm_or_si128(edges[0].last, edges[1].last), edges[2].last);
            const auto outside =
                static_cast<unsigned>(_mm_movemask_epi8(_mm_packs_epi16(firstOr, lastOr)));
            const unsigned inside = ~outside & columns;
            if (inside != 0)
                visit(r, colMin + __builtin_ctz(inside), colMin + 31 - __builtin_clz(inside));
            for (EdgeLanes& edge : edges)
                edge.nextRow();
        }
        return true;
#else
        (void)gridWidth, (void)rowFirst, (void)rowLast, (void)strictEdge, (void)visit;
        return false;
#endif
    }

    std::array<PixelCorner, 3> m_corner;
    std::int64_t m_det = 0;
    double m_gradCol = 0.0;
    double m_gradRow = 0.0;
    std::int64_t m_rowMin = 0;
    std::int64_t m_rowMax = 0;
};

} // namespace terratin::detail

#pragma once
/// @file
/// Exact geometric predicates after J. R. Shewchuk, "Adaptive Precision Floating-Point
/// Arithmetic and Fast Robust Geometric Predicates", Discrete & Computational Geometry 18 (1997).
/// Each predicate returns a value whose SIGN is exactly that of the real-number determinant of
/// its double inputs (magnitude is only an approximation). Inputs must be finite and their
/// products must not overflow or underflow (coordinates within about 1e-140..1e140).

#include "terratin/geometry/point.hpp"

namespace terratin::predicates {

/// Positive if a, b, c turn counter-clockwise, negative if clockwise, zero if collinear.
double orient2d(const Point2& a, const Point2& b, const Point2& c);

/// For a, b, c in counter-clockwise order: positive if d lies strictly inside their circumcircle,
/// negative if strictly outside, zero if the four points are cocircular. The sign flips when
/// a, b, c are clockwise.
double incircle(const Point2& a, const Point2& b, const Point2& c, const Point2& d);

} // namespace terratin::predicates

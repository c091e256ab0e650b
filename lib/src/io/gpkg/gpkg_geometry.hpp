#pragma once
/// @file
/// GeoPackage geometry blobs (GeoPackage 1.2, clause 2.1.3): the "GP" header, the srs_id and an
/// envelope, then the geometry as ISO WKB, little-endian throughout. The bytes are those GDAL
/// writes for the same geometry: an x/y/z envelope for polygons and lines, none for points
/// (a point is its own envelope).

#include "terratin/geometry/point.hpp"

#include <cstddef>
#include <cstdint>
#include <span>

namespace terratin::io::detail {

/// Size in bytes of each blob, fixed by its shape.
inline constexpr std::size_t kGpkgTriangleBytes = 8 + 48 + 1 + 4 + 4 + 4 + 4 * 24;
inline constexpr std::size_t kGpkgPointBytes = 8 + 1 + 4 + 24;
inline constexpr std::size_t kGpkgSegmentBytes = 8 + 48 + 1 + 4 + 4 + 2 * 24;

/// Polygon Z with one closed ring a, b, c, a into `out` (kGpkgTriangleBytes).
void encodeGpkgTriangle(const Point3& a, const Point3& b, const Point3& c, std::int32_t srsId,
                        std::span<std::uint8_t, kGpkgTriangleBytes> out);

/// Point Z into `out` (kGpkgPointBytes).
void encodeGpkgPoint(const Point3& p, std::int32_t srsId,
                     std::span<std::uint8_t, kGpkgPointBytes> out);

/// LineString Z from a to b into `out` (kGpkgSegmentBytes).
void encodeGpkgSegment(const Point3& a, const Point3& b, std::int32_t srsId,
                       std::span<std::uint8_t, kGpkgSegmentBytes> out);

} // namespace terratin::io::detail

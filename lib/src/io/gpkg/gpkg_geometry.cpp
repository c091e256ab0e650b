#include "gpkg_geometry.hpp"

#include <algorithm>
#include <bit>
#include <cstring>
#include <initializer_list>

namespace terratin::io::detail {

namespace {

static_assert(std::endian::native == std::endian::little,
              "the blobs are written little-endian by copying native values");

/// Flags byte of the header: bit 0 little-endian, bits 1-3 the envelope kind.
constexpr std::uint8_t kLittleEndianFlag = 0x01;
constexpr std::uint8_t kEnvelopeXyz = 2 << 1;
/// ISO WKB type codes of the Z geometries.
constexpr std::uint32_t kWkbPointZ = 1001;
constexpr std::uint32_t kWkbLineStringZ = 1002;
constexpr std::uint32_t kWkbPolygonZ = 1003;

/// Appends values at a cursor; the callers size their spans exactly.
class BlobCursor {
public:
    explicit BlobCursor(std::uint8_t* out) : m_out(out) {}
    template <class T> void put(T value) {
        std::memcpy(m_out, &value, sizeof value);
        m_out += sizeof value;
    }
    void putPoint(const Point3& p) {
        put(p.x);
        put(p.y);
        put(p.z);
    }
    void putHeader(std::int32_t srsId, std::uint8_t envelope) {
        put(std::uint8_t{'G'});
        put(std::uint8_t{'P'});
        put(std::uint8_t{0}); // version 1 is written as 0
        put(static_cast<std::uint8_t>(kLittleEndianFlag | envelope));
        put(srsId);
    }
    /// minx, maxx, miny, maxy, minz, maxz of the points.
    void putXyzEnvelope(std::initializer_list<const Point3*> points) {
        Point3 low = **points.begin();
        Point3 high = low;
        for (const Point3* p : points) {
            low = {std::min(low.x, p->x), std::min(low.y, p->y), std::min(low.z, p->z)};
            high = {std::max(high.x, p->x), std::max(high.y, p->y), std::max(high.z, p->z)};
        }
        for (const double value : {low.x, high.x, low.y, high.y, low.z, high.z})
            put(value);
    }
    void putWkbType(std::uint32_t type) {
        put(std::uint8_t{1}); // little-endian WKB
        put(type);
    }

private:
    std::uint8_t* m_out;
};

} // namespace

void encodeGpkgTriangle(const Point3& a, const Point3& b, const Point3& c, std::int32_t srsId,
                        std::span<std::uint8_t, kGpkgTriangleBytes> out) {
    BlobCursor cursor(out.data());
    cursor.putHeader(srsId, kEnvelopeXyz);
    cursor.putXyzEnvelope({&a, &b, &c});
    cursor.putWkbType(kWkbPolygonZ);
    cursor.put(std::uint32_t{1}); // rings
    cursor.put(std::uint32_t{4}); // points of the closed ring
    for (const Point3* p : {&a, &b, &c, &a})
        cursor.putPoint(*p);
}

void encodeGpkgPoint(const Point3& p, std::int32_t srsId,
                     std::span<std::uint8_t, kGpkgPointBytes> out) {
    BlobCursor cursor(out.data());
    cursor.putHeader(srsId, 0);
    cursor.putWkbType(kWkbPointZ);
    cursor.putPoint(p);
}

void encodeGpkgSegment(const Point3& a, const Point3& b, std::int32_t srsId,
                       std::span<std::uint8_t, kGpkgSegmentBytes> out) {
    BlobCursor cursor(out.data());
    cursor.putHeader(srsId, kEnvelopeXyz);
    cursor.putXyzEnvelope({&a, &b});
    cursor.putWkbType(kWkbLineStringZ);
    cursor.put(std::uint32_t{2});
    cursor.putPoint(a);
    cursor.putPoint(b);
}

} // namespace terratin::io::detail

/// @file
/// POINT10 item decoders, versions 1 and 2 (see point10_decoder.hpp).

#include "point10_decoder.hpp"

#include "laz_bytes.hpp"

#include <algorithm>

namespace terratin::io::laz {

namespace {

/// Version 2's context for a point with return number r and number of returns n: the 15
/// valid pairs (1 <= r <= n <= 5) get contexts 0-14 of their own; the invalid pairs that some
/// writers produce (numbering from 0, swapped fields, n above 5) share nearby contexts
/// instead of all falling into one. Indexed [n][r]; part of the format.
constexpr std::array<std::array<std::uint8_t, 8>, 8> kReturnContext{{
    {15, 14, 13, 12, 11, 10, 9, 8},
    {14, 0, 1, 3, 6, 10, 10, 9},
    {13, 1, 2, 4, 7, 11, 11, 10},
    {12, 3, 4, 5, 8, 12, 12, 11},
    {11, 6, 7, 8, 9, 13, 13, 12},
    {10, 10, 11, 12, 13, 14, 14, 13},
    {9, 10, 11, 12, 13, 14, 15, 14},
    {8, 9, 10, 11, 12, 13, 14, 15},
}};

/// Which fields changed, one bit each (version 2): 32 the return byte, 16 intensity,
/// 8 classification, 4 scan angle, 2 user data, 1 point source id.
/// Version 1 orders them 32 intensity, 16 return byte, then the same.
constexpr std::uint32_t kChangedSourceId = 1;
constexpr std::uint32_t kChangedUserData = 2;
constexpr std::uint32_t kChangedScanAngle = 4;
constexpr std::uint32_t kChangedClass = 8;

std::int32_t medianOfThree(const std::array<std::int32_t, 3>& v) {
    return std::max(std::min(v[0], v[1]), std::min(std::max(v[0], v[1]), v[2]));
}

} // namespace

Point10Fields Point10Fields::load(const std::byte* record) {
    Point10Fields f;
    f.x = loadLe<std::int32_t>(record);
    f.y = loadLe<std::int32_t>(record + 4);
    f.z = loadLe<std::int32_t>(record + 8);
    f.intensity = loadLe<std::uint16_t>(record + 12);
    f.returnByte = loadLe<std::uint8_t>(record + 14);
    f.classByte = loadLe<std::uint8_t>(record + 15);
    f.scanAngle = loadLe<std::uint8_t>(record + 16);
    f.userData = loadLe<std::uint8_t>(record + 17);
    f.sourceId = loadLe<std::uint16_t>(record + 18);
    return f;
}

void Point10Fields::store(std::byte* record) const {
    storeLe(record, x);
    storeLe(record + 4, y);
    storeLe(record + 8, z);
    storeLe(record + 12, intensity);
    record[14] = static_cast<std::byte>(returnByte);
    record[15] = static_cast<std::byte>(classByte);
    record[16] = static_cast<std::byte>(scanAngle);
    record[17] = static_cast<std::byte>(userData);
    storeLe(record + 18, sourceId);
}

// ---- version 1 --------------------------------------------------------------------------

Point10V1Decoder::Point10V1Decoder()
    : m_dx(32), m_dy(32, 20), m_z(32, 20), m_intensity(16), m_scanAngle(8, 2), m_sourceId(16),
      m_changed(64) {}

void Point10V1Decoder::start(const std::byte* first) {
    m_last = Point10Fields::load(first);
    m_recentDx.fill(0);
    m_recentDy.fill(0);
    m_nextRecent = 0;
    for (IntegerDecoder* ic : {&m_dx, &m_dy, &m_z, &m_intensity, &m_scanAngle, &m_sourceId})
        ic->reset();
    m_changed.reset();
    m_returnByteModels.reset();
    m_classModels.reset();
    m_userDataModels.reset();
}

void Point10V1Decoder::decode(RangeDecoder& decoder, std::byte* out) {
    // x, y, z first; the magnitude class of each correction picks the context of the next.
    const std::int32_t dx = m_dx.decode(decoder, medianOfThree(m_recentDx));
    m_last.x = wrappingAdd(m_last.x, dx);
    std::uint32_t coordinateClass = m_dx.lastClass();
    const std::int32_t dy = m_dy.decode(decoder, medianOfThree(m_recentDy),
                                        std::min<std::uint32_t>(coordinateClass, 19));
    m_last.y = wrappingAdd(m_last.y, dy);
    coordinateClass = (coordinateClass + m_dy.lastClass()) / 2;
    m_last.z = m_z.decode(decoder, m_last.z, std::min<std::uint32_t>(coordinateClass, 19));
    decodeChangedFields(decoder, coordinateClass);
    m_recentDx[m_nextRecent] = dx;
    m_recentDy[m_nextRecent] = dy;
    m_nextRecent = m_nextRecent == 2 ? 0 : m_nextRecent + 1;
    m_last.store(out);
}

void Point10V1Decoder::decodeChangedFields(RangeDecoder& decoder, std::uint32_t coordinateClass) {
    const std::uint32_t changed = decoder.decodeSymbol(m_changed);
    if (changed == 0)
        return;
    if (changed & 32)
        m_last.intensity =
            static_cast<std::uint16_t>(m_intensity.decode(decoder, m_last.intensity));
    if (changed & 16)
        m_last.returnByte = static_cast<std::uint8_t>(
            decoder.decodeSymbol(m_returnByteModels.at(m_last.returnByte)));
    if (changed & kChangedClass)
        m_last.classByte =
            static_cast<std::uint8_t>(decoder.decodeSymbol(m_classModels.at(m_last.classByte)));
    if (changed & kChangedScanAngle)
        m_last.scanAngle = static_cast<std::uint8_t>(
            m_scanAngle.decode(decoder, m_last.scanAngle, coordinateClass < 3 ? 1 : 0));
    if (changed & kChangedUserData)
        m_last.userData =
            static_cast<std::uint8_t>(decoder.decodeSymbol(m_userDataModels.at(m_last.userData)));
    if (changed & kChangedSourceId)
        m_last.sourceId = static_cast<std::uint16_t>(m_sourceId.decode(decoder, m_last.sourceId));
}

// ---- version 2 --------------------------------------------------------------------------

Point10V2Decoder::Point10V2Decoder()
    : m_changed(64), m_intensity(16, 4), m_scanAngle{SymbolModel(256), SymbolModel(256)},
      m_sourceId(16), m_dx(32, 2), m_dy(32, 22), m_z(32, 20) {}

void Point10V2Decoder::start(const std::byte* first) {
    m_last = Point10Fields::load(first);
    // The intensity is predicted per return context from zero, the first point's included:
    // the writer starts from an intensity of 0, not from the raw first point's.
    m_last.intensity = 0;
    m_lastIntensity.fill(0);
    m_lastZ.fill(0);
    for (RunningMedian5& median : m_dxMedian)
        median.reset();
    for (RunningMedian5& median : m_dyMedian)
        median.reset();
    m_changed.reset();
    m_intensity.reset();
    m_scanAngle[0].reset();
    m_scanAngle[1].reset();
    m_sourceId.reset();
    m_returnByteModels.reset();
    m_classModels.reset();
    m_userDataModels.reset();
    m_dx.reset();
    m_dy.reset();
    m_z.reset();
}

void Point10V2Decoder::decode(RangeDecoder& decoder, std::byte* out) {
    const std::uint32_t changed = decoder.decodeSymbol(m_changed);
    if (changed != 0)
        decodeChangedFields(decoder, changed);
    decodeCoordinates(decoder);
    m_last.store(out);
}

void Point10V2Decoder::decodeChangedFields(RangeDecoder& decoder, std::uint32_t changed) {
    if (changed & 32)
        m_last.returnByte = static_cast<std::uint8_t>(
            decoder.decodeSymbol(m_returnByteModels.at(m_last.returnByte)));
    const unsigned returnNumber = m_last.returnByte & 7u;
    const unsigned returnCount = (m_last.returnByte >> 3) & 7u;
    const unsigned context = kReturnContext[returnCount][returnNumber];
    if (changed & 16) {
        m_lastIntensity[context] = static_cast<std::uint16_t>(
            m_intensity.decode(decoder, m_lastIntensity[context], std::min(context, 3u)));
    }
    m_last.intensity = m_lastIntensity[context];
    if (changed & kChangedClass)
        m_last.classByte =
            static_cast<std::uint8_t>(decoder.decodeSymbol(m_classModels.at(m_last.classByte)));
    if (changed & kChangedScanAngle) {
        // Coded as a byte difference, with one model per scan direction (bit 6).
        const std::uint32_t step = decoder.decodeSymbol(m_scanAngle[(m_last.returnByte >> 6) & 1u]);
        m_last.scanAngle = static_cast<std::uint8_t>(m_last.scanAngle + step);
    }
    if (changed & kChangedUserData)
        m_last.userData =
            static_cast<std::uint8_t>(decoder.decodeSymbol(m_userDataModels.at(m_last.userData)));
    if (changed & kChangedSourceId)
        m_last.sourceId = static_cast<std::uint16_t>(m_sourceId.decode(decoder, m_last.sourceId));
}

void Point10V2Decoder::decodeCoordinates(RangeDecoder& decoder) {
    const unsigned returnNumber = m_last.returnByte & 7u;
    const unsigned returnCount = (m_last.returnByte >> 3) & 7u;
    const unsigned context = kReturnContext[returnCount][returnNumber];
    const unsigned level =
        returnCount > returnNumber ? returnCount - returnNumber : returnNumber - returnCount;
    const std::uint32_t single = returnCount == 1 ? 1 : 0;

    const std::int32_t dx = m_dx.decode(decoder, m_dxMedian[context].middle(), single);
    m_last.x = wrappingAdd(m_last.x, dx);
    m_dxMedian[context].add(dx);

    // The magnitude classes of the corrections so far pick the context of the next one
    // (even classes only, capped), halving the models needed.
    const std::uint32_t xClass = m_dx.lastClass();
    const std::uint32_t yContext = single + (xClass < 20 ? (xClass & ~1u) : 20);
    const std::int32_t dy = m_dy.decode(decoder, m_dyMedian[context].middle(), yContext);
    m_last.y = wrappingAdd(m_last.y, dy);
    m_dyMedian[context].add(dy);

    const std::uint32_t xyClass = (m_dx.lastClass() + m_dy.lastClass()) / 2;
    const std::uint32_t zContext = single + (xyClass < 18 ? (xyClass & ~1u) : 18);
    m_last.z = m_z.decode(decoder, m_lastZ[level], zContext);
    m_lastZ[level] = m_last.z;
}

} // namespace terratin::io::laz

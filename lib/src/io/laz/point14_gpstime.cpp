/// @file
/// The GPS time layer of POINT14 version 3 (see point14_gpstime.hpp).

#include "point14_gpstime.hpp"

#include "item_context.hpp"

namespace terratin::io::laz {

namespace {

/// Adds a signed 32-bit difference to a time's bit pattern, wrapping as the writer does.
std::uint64_t advanced(std::uint64_t time, std::int32_t difference) {
    return time + static_cast<std::uint64_t>(static_cast<std::int64_t>(difference));
}

// Symbols of the "multiple" model: 0 an outlier near the time, 1 a new step, 2-499 that many
// steps, 500 the largest multiple, 501-510 -1 to -10 steps, 511 a new sequence (full time),
// 512-514 switch to sequence +1, +2, +3.
constexpr std::int32_t kLargestMultiple = 500;
constexpr std::int32_t kSmallestMultiple = -10;
constexpr std::uint32_t kNewSequence = kLargestMultiple - kSmallestMultiple + 1;
constexpr std::uint32_t kMultipleSymbols = kNewSequence + 4;
/// After a zero step: 0 a new step, 1 a new sequence, 2-4 switch to sequence +1, +2, +3.
constexpr std::uint32_t kAfterZeroSymbols = 5;
constexpr std::uint32_t kAfterZeroNewSequence = 1;
/// An outlier becomes the new step only after more than this many in a row.
constexpr std::int32_t kOutlierRunLimit = 3;

} // namespace

Point14GpsTime::Point14GpsTime()
    : m_multiple(kMultipleSymbols), m_afterZeroStep(kAfterZeroSymbols), m_difference(32, 9) {}

void Point14GpsTime::start(std::uint64_t first) {
    m_time = {first, 0, 0, 0};
    m_step.fill(0);
    m_outlierRun.fill(0);
    m_current = 0;
    m_newest = 0;
    m_multiple.reset();
    m_afterZeroStep.reset();
    m_difference.reset();
}

void Point14GpsTime::decode(RangeDecoder& decoder) {
    // A writer switches sequence at most once per time: only to a sequence whose time is
    // within a 32-bit step. A second switch means a corrupt stream (and could loop forever).
    bool done = m_step[m_current] == 0 ? decodeAfterZeroStep(decoder) : decodeWithStep(decoder);
    if (!done) {
        done = m_step[m_current] == 0 ? decodeAfterZeroStep(decoder) : decodeWithStep(decoder);
        if (!done)
            decoder.markCorrupt();
    }
}

bool Point14GpsTime::decodeAfterZeroStep(RangeDecoder& decoder) {
    const std::uint32_t symbol = decoder.decodeSymbol(m_afterZeroStep);
    if (symbol == 0) {
        m_step[m_current] = m_difference.decode(decoder, 0, 0);
        m_time[m_current] = advanced(m_time[m_current], m_step[m_current]);
        m_outlierRun[m_current] = 0;
    } else if (symbol == kAfterZeroNewSequence) {
        startSequence(decoder);
    } else {
        m_current = (m_current + symbol - kAfterZeroNewSequence) & 3u;
        return false;
    }
    return true;
}

bool Point14GpsTime::decodeWithStep(RangeDecoder& decoder) {
    const std::uint32_t symbol = decoder.decodeSymbol(m_multiple);
    if (symbol == 1) {
        m_time[m_current] =
            advanced(m_time[m_current], m_difference.decode(decoder, m_step[m_current], 1));
        m_outlierRun[m_current] = 0;
    } else if (symbol < kNewSequence) {
        m_time[m_current] = advanced(m_time[m_current], decodeMultipleOfStep(decoder, symbol));
    } else if (symbol == kNewSequence) {
        startSequence(decoder);
    } else {
        m_current = (m_current + symbol - kNewSequence) & 3u;
        return false;
    }
    return true;
}

std::int32_t Point14GpsTime::decodeMultipleOfStep(RangeDecoder& decoder, std::uint32_t symbol) {
    const std::int32_t step = m_step[m_current];
    if (symbol == 0) {
        const std::int32_t difference = m_difference.decode(decoder, 0, 7);
        countOutlier(difference);
        return difference;
    }
    const auto multiple = static_cast<std::int32_t>(symbol);
    if (multiple < kLargestMultiple)
        return m_difference.decode(decoder, wrappingMultiply(multiple, step),
                                   multiple < 10 ? 2 : 3);
    if (multiple == kLargestMultiple) {
        const std::int32_t difference =
            m_difference.decode(decoder, wrappingMultiply(kLargestMultiple, step), 4);
        countOutlier(difference);
        return difference;
    }
    // 501-510: the negative multiples -1 .. -10.
    const std::int32_t negative = kLargestMultiple - multiple;
    if (negative > kSmallestMultiple)
        return m_difference.decode(decoder, wrappingMultiply(negative, step), 5);
    const std::int32_t difference =
        m_difference.decode(decoder, wrappingMultiply(kSmallestMultiple, step), 6);
    countOutlier(difference);
    return difference;
}

void Point14GpsTime::countOutlier(std::int32_t difference) {
    if (++m_outlierRun[m_current] > kOutlierRunLimit) {
        m_step[m_current] = difference;
        m_outlierRun[m_current] = 0;
    }
}

void Point14GpsTime::startSequence(RangeDecoder& decoder) {
    // The high 32 bits predicted from the current sequence's, the low 32 raw.
    m_newest = (m_newest + 1) & 3u;
    const auto currentHigh = static_cast<std::int32_t>(m_time[m_current] >> 32);
    const auto high = static_cast<std::uint32_t>(m_difference.decode(decoder, currentHigh, 8));
    m_time[m_newest] = (static_cast<std::uint64_t>(high) << 32) | decoder.readInt();
    m_current = m_newest;
    m_step[m_current] = 0;
    m_outlierRun[m_current] = 0;
}

} // namespace terratin::io::laz

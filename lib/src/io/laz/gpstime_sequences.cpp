/// @file
/// The GPS time sequences of GPSTIME11 v2 and POINT14 v3 (see gpstime_sequences.hpp).

#include "gpstime_sequences.hpp"

#include "item_context.hpp"

namespace terratin::io::laz {

namespace {

// Codes of the "multiple" model: 0 an outlier near the time, 1 one step, 2-499 that many
// steps, 500 the largest multiple, 501-510 -1 to -10 steps; then (GPSTIME11 v2 only) 511
// unchanged; then a new sequence (full time) and the switches to sequence +1, +2, +3.
constexpr std::int32_t kLargestMultiple = 500;
constexpr std::int32_t kSmallestMultiple = -10;
/// The codes below this one advance the current time by a multiple of its step.
constexpr std::uint32_t kStepCodes = kLargestMultiple - kSmallestMultiple + 1;
/// After a zero step the codes are (GPSTIME11 v2 only) 0 unchanged, then a new step, a new
/// sequence and the switches to sequence +1, +2, +3.
constexpr std::uint32_t kSwitchCodes = 3;

} // namespace

GpsTimeSequences::GpsTimeSequences(GpsTimeCodes codes)
    : m_unchangedCodes(codes == GpsTimeCodes::WithUnchanged ? 1 : 0),
      m_multiple(kStepCodes + m_unchangedCodes + 1 + kSwitchCodes),
      m_afterZeroStep(m_unchangedCodes + 2 + kSwitchCodes), m_difference(32, 9) {}

void GpsTimeSequences::start(std::uint64_t first) {
    m_time = {first, 0, 0, 0};
    m_step.fill(0);
    m_outlierRun.fill(0);
    m_current = 0;
    m_newest = 0;
    m_multiple.reset();
    m_afterZeroStep.reset();
    m_difference.reset();
}

bool GpsTimeSequences::decodeAfterZeroStep(RangeDecoder& decoder) {
    const std::uint32_t symbol = decoder.decodeSymbol(m_afterZeroStep);
    const std::uint32_t newStep = m_unchangedCodes;
    const std::uint32_t newSequence = newStep + 1;
    if (symbol == newStep) {
        m_step[m_current] = m_difference.decode(decoder, 0, 0);
        m_time[m_current] = advancedTime(m_time[m_current], m_step[m_current]);
        m_outlierRun[m_current] = 0;
    } else if (symbol == newSequence) {
        startSequence(decoder);
    } else if (symbol > newSequence) {
        switchSequence(symbol - newSequence);
        return false;
    }
    return true; // includes GPSTIME11 v2's "unchanged"
}

bool GpsTimeSequences::decodeWithStep(RangeDecoder& decoder) {
    const std::uint32_t symbol = decoder.decodeSymbol(m_multiple);
    if (symbol == 1) {
        m_time[m_current] =
            advancedTime(m_time[m_current], m_difference.decode(decoder, m_step[m_current], 1));
        m_outlierRun[m_current] = 0;
        return true;
    }
    if (symbol < kStepCodes) {
        m_time[m_current] = advancedTime(m_time[m_current], decodeMultipleOfStep(decoder, symbol));
        return true;
    }
    const std::uint32_t newSequence = kStepCodes + m_unchangedCodes;
    if (symbol == newSequence) {
        startSequence(decoder);
    } else if (symbol > newSequence) {
        switchSequence(symbol - newSequence);
        return false;
    }
    return true; // includes GPSTIME11 v2's "unchanged"
}

std::int32_t GpsTimeSequences::decodeMultipleOfStep(RangeDecoder& decoder, std::uint32_t symbol) {
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

void GpsTimeSequences::countOutlier(std::int32_t difference) {
    if (++m_outlierRun[m_current] > kOutlierRunLimit) {
        m_step[m_current] = difference;
        m_outlierRun[m_current] = 0;
    }
}

void GpsTimeSequences::startSequence(RangeDecoder& decoder) {
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

/// @file
/// GPSTIME11 item decoders, versions 1 and 2 (see gpstime_decoder.hpp).

#include "gpstime_decoder.hpp"

#include "item_context.hpp"
#include "laz_bytes.hpp"

namespace terratin::io::laz {

namespace {

/// Adds a signed 32-bit difference to a time's bit pattern, wrapping as the writer does.
std::uint64_t advanced(std::uint64_t time, std::int32_t difference) {
    return time + static_cast<std::uint64_t>(static_cast<std::int64_t>(difference));
}

// Version 1: symbols of the "multiple" model (512). 0: a quarter step, 1: a new step,
// 2-508: that many steps, 509: the largest multiple, 510: a full 64-bit time, 511: unchanged.
constexpr std::uint32_t kV1Symbols = 512;
constexpr std::uint32_t kV1LargestMultiple = kV1Symbols - 3;
constexpr std::uint32_t kV1FullTime = kV1Symbols - 2;

// Version 2: symbols of the "multiple" model. 0: an outlier near the time, 1: a new step,
// 2-499: that many steps, 500: the largest multiple, 501-510: -1 to -10 steps,
// 511: unchanged, 512: a new sequence (full time), 513-515: switch to sequence +1, +2, +3.
constexpr std::int32_t kV2LargestMultiple = 500;
constexpr std::int32_t kV2SmallestMultiple = -10;
constexpr std::uint32_t kV2Unchanged = kV2LargestMultiple - kV2SmallestMultiple + 1;
constexpr std::uint32_t kV2NewSequence = kV2Unchanged + 1;
constexpr std::uint32_t kV2Symbols = kV2Unchanged + 5;
/// After a zero step the alphabet is 0 unchanged, 1 a new step, 2 a new sequence,
/// 3-5 switch to sequence +1, +2, +3.
constexpr std::uint32_t kV2AfterZeroSymbols = 6;
/// An outlier becomes the new step only after more than this many in a row.
constexpr std::int32_t kOutlierRunLimit = 3;

} // namespace

// ---- version 1 --------------------------------------------------------------------------

GpsTime11V1Decoder::GpsTime11V1Decoder()
    : m_multiple(kV1Symbols), m_afterZeroStep(3), m_difference(32, 6) {}

void GpsTime11V1Decoder::start(const std::byte* first) {
    m_time = loadLe<std::uint64_t>(first);
    m_step = 0;
    m_outlierRun = 0;
    m_multiple.reset();
    m_afterZeroStep.reset();
    m_difference.reset();
}

void GpsTime11V1Decoder::decode(RangeDecoder& decoder, std::byte* out) {
    if (m_step == 0) {
        const std::uint32_t symbol = decoder.decodeSymbol(m_afterZeroStep);
        if (symbol == 1) {
            m_step = m_difference.decode(decoder, 0, 0);
            m_time = advanced(m_time, m_step);
        } else if (symbol == 2) {
            m_time = decoder.readInt64();
        }
    } else {
        decodeWithStep(decoder);
    }
    storeLe(out, m_time);
}

void GpsTime11V1Decoder::decodeWithStep(RangeDecoder& decoder) {
    const std::uint32_t symbol = decoder.decodeSymbol(m_multiple);
    if (symbol == kV1FullTime) {
        m_time = decoder.readInt64();
        return;
    }
    if (symbol > kV1FullTime)
        return; // unchanged
    std::int32_t difference = 0;
    if (symbol == 1) {
        difference = m_difference.decode(decoder, m_step, 1);
        m_step = difference;
        m_outlierRun = 0;
    } else if (symbol == 0) {
        difference = m_difference.decode(decoder, m_step / 4, 2);
        if (++m_outlierRun > kOutlierRunLimit) {
            m_step = difference;
            m_outlierRun = 0;
        }
    } else {
        const auto multiple = static_cast<std::int32_t>(symbol);
        const std::uint32_t context = symbol < 10 ? 3 : symbol < 50 ? 4 : 5;
        difference = m_difference.decode(decoder, wrappingMultiply(multiple, m_step), context);
        if (symbol == kV1LargestMultiple && ++m_outlierRun > kOutlierRunLimit) {
            m_step = difference;
            m_outlierRun = 0;
        }
    }
    m_time = advanced(m_time, difference);
}

// ---- version 2 --------------------------------------------------------------------------

GpsTime11V2Decoder::GpsTime11V2Decoder()
    : m_multiple(kV2Symbols), m_afterZeroStep(kV2AfterZeroSymbols), m_difference(32, 9) {}

void GpsTime11V2Decoder::start(const std::byte* first) {
    m_time = {loadLe<std::uint64_t>(first), 0, 0, 0};
    m_step.fill(0);
    m_outlierRun.fill(0);
    m_current = 0;
    m_newest = 0;
    m_multiple.reset();
    m_afterZeroStep.reset();
    m_difference.reset();
}

void GpsTime11V2Decoder::decode(RangeDecoder& decoder, std::byte* out) {
    // A writer switches sequence at most once per point: it switches only to a sequence
    // whose time is within a 32-bit step. A second switch means a corrupt stream.
    bool done = m_step[m_current] == 0 ? decodeAfterZeroStep(decoder) : decodeWithStep(decoder);
    if (!done) {
        done = m_step[m_current] == 0 ? decodeAfterZeroStep(decoder) : decodeWithStep(decoder);
        if (!done)
            decoder.markCorrupt();
    }
    storeLe(out, m_time[m_current]);
}

bool GpsTime11V2Decoder::decodeAfterZeroStep(RangeDecoder& decoder) {
    const std::uint32_t symbol = decoder.decodeSymbol(m_afterZeroStep);
    if (symbol == 1) {
        m_step[m_current] = m_difference.decode(decoder, 0, 0);
        m_time[m_current] = advanced(m_time[m_current], m_step[m_current]);
        m_outlierRun[m_current] = 0;
    } else if (symbol == 2) {
        startSequence(decoder);
    } else if (symbol > 2) {
        m_current = (m_current + symbol - 2) & 3u;
        return false;
    }
    return true;
}

bool GpsTime11V2Decoder::decodeWithStep(RangeDecoder& decoder) {
    const std::uint32_t symbol = decoder.decodeSymbol(m_multiple);
    if (symbol == 1) {
        m_time[m_current] =
            advanced(m_time[m_current], m_difference.decode(decoder, m_step[m_current], 1));
        m_outlierRun[m_current] = 0;
    } else if (symbol < kV2Unchanged) {
        m_time[m_current] = advanced(m_time[m_current], decodeMultipleOfStep(decoder, symbol));
    } else if (symbol == kV2NewSequence) {
        startSequence(decoder);
    } else if (symbol > kV2NewSequence) {
        m_current = (m_current + symbol - kV2NewSequence) & 3u;
        return false;
    }
    return true;
}

std::int32_t GpsTime11V2Decoder::decodeMultipleOfStep(RangeDecoder& decoder, std::uint32_t symbol) {
    const std::int32_t step = m_step[m_current];
    if (symbol == 0) {
        const std::int32_t difference = m_difference.decode(decoder, 0, 7);
        countOutlier(difference);
        return difference;
    }
    const auto multiple = static_cast<std::int32_t>(symbol);
    if (multiple < kV2LargestMultiple)
        return m_difference.decode(decoder, wrappingMultiply(multiple, step),
                                   multiple < 10 ? 2 : 3);
    if (multiple == kV2LargestMultiple) {
        const std::int32_t difference =
            m_difference.decode(decoder, wrappingMultiply(kV2LargestMultiple, step), 4);
        countOutlier(difference);
        return difference;
    }
    // 501-510: the negative multiples -1 .. -10.
    const std::int32_t negative = kV2LargestMultiple - multiple;
    if (negative > kV2SmallestMultiple)
        return m_difference.decode(decoder, wrappingMultiply(negative, step), 5);
    const std::int32_t difference =
        m_difference.decode(decoder, wrappingMultiply(kV2SmallestMultiple, step), 6);
    countOutlier(difference);
    return difference;
}

void GpsTime11V2Decoder::countOutlier(std::int32_t difference) {
    if (++m_outlierRun[m_current] > kOutlierRunLimit) {
        m_step[m_current] = difference;
        m_outlierRun[m_current] = 0;
    }
}

void GpsTime11V2Decoder::startSequence(RangeDecoder& decoder) {
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

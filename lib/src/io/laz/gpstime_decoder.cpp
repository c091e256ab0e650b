/// @file
/// GPSTIME11 item decoders, versions 1 and 2 (see gpstime_decoder.hpp).

#include "gpstime_decoder.hpp"

#include "item_context.hpp"
#include "laz_bytes.hpp"

namespace terratin::io::laz {

namespace {

// Version 1: symbols of the "multiple" model (512). 0: a quarter step, 1: a new step,
// 2-508: that many steps, 509: the largest multiple, 510: a full 64-bit time, 511: unchanged.
constexpr std::uint32_t kV1Symbols = 512;
constexpr std::uint32_t kV1LargestMultiple = kV1Symbols - 3;
constexpr std::uint32_t kV1FullTime = kV1Symbols - 2;

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
            m_time = advancedTime(m_time, m_step);
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
    m_time = advancedTime(m_time, difference);
}

// ---- version 2 --------------------------------------------------------------------------

void GpsTime11V2Decoder::start(const std::byte* first) {
    m_sequences.start(loadLe<std::uint64_t>(first));
}

void GpsTime11V2Decoder::decode(RangeDecoder& decoder, std::byte* out) {
    m_sequences.decode(decoder);
    storeLe(out, m_sequences.current());
}

} // namespace terratin::io::laz

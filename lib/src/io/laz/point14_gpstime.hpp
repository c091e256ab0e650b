#pragma once
/// @file
/// The GPS time layer of POINT14 version 3, for one scanner channel. As in GPSTIME11 version 2
/// (gpstime_decoder.hpp) the 64-bit pattern of the double is predicted as an integer: a
/// multiple of the last step plus a correction, a new 32-bit step, or a new sequence; four
/// sequences are kept for files that interleave flight lines. Unlike version 2 the layer holds
/// only the points whose time changed (the returns-and-xy layer says which), so there is no
/// "unchanged" code, which shifts the codes after it by one.

#include "integer_decoder.hpp"
#include "range_decoder.hpp"

#include <array>
#include <cstdint>

namespace terratin::io::laz {

class Point14GpsTime {
public:
    Point14GpsTime();
    /// A new chunk or scanner channel whose last time was `first` (bit pattern); every model
    /// back to its initial state.
    void start(std::uint64_t first);
    /// The next changed time.
    void decode(RangeDecoder& decoder);
    /// The time decoded last (bit pattern of the double).
    [[nodiscard]] std::uint64_t current() const { return m_time[m_current]; }

private:
    /// Whether the time is done; false: the current sequence changed, decode again.
    bool decodeAfterZeroStep(RangeDecoder& decoder);
    bool decodeWithStep(RangeDecoder& decoder);
    [[nodiscard]] std::int32_t decodeMultipleOfStep(RangeDecoder& decoder, std::uint32_t symbol);
    void countOutlier(std::int32_t difference);
    void startSequence(RangeDecoder& decoder);

    std::array<std::uint64_t, 4> m_time{};
    std::array<std::int32_t, 4> m_step{};
    std::array<std::int32_t, 4> m_outlierRun{};
    std::uint32_t m_current = 0;
    std::uint32_t m_newest = 0;
    SymbolModel m_multiple;
    SymbolModel m_afterZeroStep;
    IntegerDecoder m_difference;
};

} // namespace terratin::io::laz

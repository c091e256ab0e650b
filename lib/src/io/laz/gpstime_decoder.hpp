#pragma once
/// @file
/// Decoders of the GPSTIME11 item: the 8-byte GPS time (a double) of point formats 1, 3, 4, 5
/// (LAS 1.4 R15, tables 8-12). LASzip never decodes the double as a number: it predicts the
/// 64-bit pattern as an integer, since consecutive pulses differ by a nearly constant step.
/// A time is coded as a multiple of the last step plus a correction, as a new 32-bit step,
/// or in full. Version 2 also keeps four sequences, for files that interleave flight lines
/// or scanners, and codes switches between them (Isenburg 2013).

#include "integer_decoder.hpp"
#include "range_decoder.hpp"

#include <array>
#include <cstddef>
#include <cstdint>

namespace terratin::io::laz {

class GpsTime11V1Decoder {
public:
    GpsTime11V1Decoder();
    void start(const std::byte* first);
    void decode(RangeDecoder& decoder, std::byte* out);

private:
    void decodeWithStep(RangeDecoder& decoder);

    std::uint64_t m_time = 0;
    std::int32_t m_step = 0;
    std::int32_t m_outlierRun = 0;
    SymbolModel m_multiple;
    SymbolModel m_afterZeroStep;
    IntegerDecoder m_difference;
};

class GpsTime11V2Decoder {
public:
    GpsTime11V2Decoder();
    void start(const std::byte* first);
    void decode(RangeDecoder& decoder, std::byte* out);

private:
    /// Whether the point is done; false: the current sequence changed, decode again.
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

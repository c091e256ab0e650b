#pragma once
/// @file
/// Decoders of the GPSTIME11 item: the 8-byte GPS time (a double) of point formats 1, 3, 4, 5
/// (LAS 1.4 R15, tables 8-12). Both versions predict the double's 64-bit pattern as an integer
/// (see gpstime_sequences.hpp). Version 1 keeps one sequence and codes a time as a multiple of
/// the last step plus a correction, as a new 32-bit step, or in full; version 2 keeps four, and
/// shares its coding with POINT14's GPS time layer (GpsTimeSequences).

#include "gpstime_sequences.hpp"
#include "integer_decoder.hpp"
#include "range_decoder.hpp"

#include <cstddef>
#include <cstdint>

namespace terratin::io::laz {

/// Version 1: one sequence.
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

/// Version 2: every point's time coded through the four sequences, "unchanged" included.
class GpsTime11V2Decoder {
public:
    void start(const std::byte* first);
    void decode(RangeDecoder& decoder, std::byte* out);

private:
    GpsTimeSequences m_sequences{GpsTimeCodes::WithUnchanged};
};

} // namespace terratin::io::laz

#pragma once
/// @file
/// Decoder of the WAVEPACKET13 item, version 1: the 29 bytes that point formats 4 and 5 add
/// to describe a point's waveform (LAS 1.4 R15, table 12): u8 wave packet descriptor index,
/// u64 byte offset to the waveform data, u32 packet size in bytes, f32 return point location,
/// f32 x(t), y(t), z(t). The descriptor index is one adaptive symbol; the offset is coded as
/// "same as the last", "right after the last packet", a 32-bit step or in full; the other
/// four fields are integer-predicted from their last bit patterns.

#include "integer_decoder.hpp"
#include "range_decoder.hpp"

#include <array>
#include <cstddef>
#include <cstdint>

namespace terratin::io::laz {

class WavePacket13V1Decoder {
public:
    WavePacket13V1Decoder();
    void start(const std::byte* first);
    void decode(RangeDecoder& decoder, std::byte* out);

private:
    std::uint64_t m_offset = 0;
    std::uint32_t m_packetSize = 0;
    /// Return point location and x(t), y(t), z(t): floats, predicted as their bit patterns.
    std::array<std::int32_t, 4> m_shape{};
    std::int32_t m_lastOffsetStep = 0;
    std::uint32_t m_lastOffsetKind = 0;
    SymbolModel m_descriptorIndex;
    /// How the offset is coded, one model per how the previous one was.
    std::array<SymbolModel, 4> m_offsetKind;
    IntegerDecoder m_offsetStep;
    IntegerDecoder m_packetSizeValue;
    IntegerDecoder m_returnPoint;
    IntegerDecoder m_xyz;
};

} // namespace terratin::io::laz

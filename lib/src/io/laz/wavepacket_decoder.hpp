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

/// Bytes of a wave packet record.
inline constexpr std::size_t kWavePacketSize = 29;

/// The models of the wave packet coding and the two values it carries from one packet to the
/// next. WAVEPACKET14 (version 3) codes packets the same way, with one set of these per
/// scanner channel.
struct WavePacketModels {
    WavePacketModels();
    /// Back to their initial state, as at the start of every chunk.
    void reset();

    SymbolModel descriptorIndex;
    /// How the offset is coded, one model per how the previous one was.
    std::array<SymbolModel, 4> offsetKind;
    IntegerDecoder offsetStep;
    IntegerDecoder packetSize;
    /// Return point location and x(t), y(t), z(t): floats, predicted as their bit patterns.
    IntegerDecoder returnPoint;
    IntegerDecoder xyz;
    std::int32_t lastOffsetStep = 0;
    std::uint32_t lastOffsetKind = 0;
};

/// Decodes the packet that follows the packet `last` into `out` (kWavePacketSize bytes each;
/// `out` may be `last`).
void decodeWavePacket(RangeDecoder& decoder, WavePacketModels& models, const std::byte* last,
                      std::byte* out);

class WavePacket13V1Decoder {
public:
    void start(const std::byte* first);
    void decode(RangeDecoder& decoder, std::byte* out);

private:
    std::array<std::byte, kWavePacketSize> m_last{};
    WavePacketModels m_models;
};

} // namespace terratin::io::laz

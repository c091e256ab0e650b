/// @file
/// WAVEPACKET13 item decoder, version 1 (see wavepacket_decoder.hpp).

#include "wavepacket_decoder.hpp"

#include "laz_bytes.hpp"

namespace terratin::io::laz {

namespace {
/// The four ways an offset is coded.
constexpr std::uint32_t kSameOffset = 0;
constexpr std::uint32_t kAfterLastPacket = 1;
constexpr std::uint32_t kOffsetStep = 2;
} // namespace

WavePacket13V1Decoder::WavePacket13V1Decoder()
    : m_descriptorIndex(256), m_offsetKind{SymbolModel(4), SymbolModel(4), SymbolModel(4),
                                           SymbolModel(4)},
      m_offsetStep(32), m_packetSizeValue(32), m_returnPoint(32), m_xyz(32, 3) {}

void WavePacket13V1Decoder::start(const std::byte* first) {
    // Byte 0, the descriptor index, has an adaptive model and no prediction.
    m_offset = loadLe<std::uint64_t>(first + 1);
    m_packetSize = loadLe<std::uint32_t>(first + 9);
    for (std::size_t i = 0; i < 4; ++i)
        m_shape[i] = loadLe<std::int32_t>(first + 13 + 4 * i);
    m_lastOffsetStep = 0;
    m_lastOffsetKind = kSameOffset;
    m_descriptorIndex.reset();
    for (SymbolModel& model : m_offsetKind)
        model.reset();
    for (IntegerDecoder* ic : {&m_offsetStep, &m_packetSizeValue, &m_returnPoint, &m_xyz})
        ic->reset();
}

void WavePacket13V1Decoder::decode(RangeDecoder& decoder, std::byte* out) {
    out[0] = static_cast<std::byte>(decoder.decodeSymbol(m_descriptorIndex));
    m_lastOffsetKind = decoder.decodeSymbol(m_offsetKind[m_lastOffsetKind]);
    if (m_lastOffsetKind == kAfterLastPacket) {
        m_offset += m_packetSize;
    } else if (m_lastOffsetKind == kOffsetStep) {
        m_lastOffsetStep = m_offsetStep.decode(decoder, m_lastOffsetStep);
        m_offset += static_cast<std::uint64_t>(static_cast<std::int64_t>(m_lastOffsetStep));
    } else if (m_lastOffsetKind != kSameOffset) {
        m_offset = decoder.readInt64();
    }
    m_packetSize = static_cast<std::uint32_t>(
        m_packetSizeValue.decode(decoder, static_cast<std::int32_t>(m_packetSize)));
    m_shape[0] = m_returnPoint.decode(decoder, m_shape[0]);
    for (std::uint32_t axis = 0; axis < 3; ++axis)
        m_shape[axis + 1] = m_xyz.decode(decoder, m_shape[axis + 1], axis);
    storeLe(out + 1, m_offset);
    storeLe(out + 9, m_packetSize);
    for (std::size_t i = 0; i < 4; ++i)
        storeLe(out + 13 + 4 * i, m_shape[i]);
}

} // namespace terratin::io::laz

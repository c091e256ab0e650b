/// @file
/// WAVEPACKET14 item decoder, version 3 (see wavepacket14_decoder.hpp).

#include "wavepacket14_decoder.hpp"

#include <cstring>

namespace terratin::io::laz {

WavePacket14V3Decoder::WavePacket14V3Decoder(bool wanted)
    : m_wanted(wanted), m_layers{LayerStream("wave packet")},
      m_contexts([] { return std::make_unique<WavePacketModels>(); }) {}

void WavePacket14V3Decoder::start(const std::byte* first,
                                  std::span<const std::span<const std::byte>> layers,
                                  std::size_t context) {
    m_layers[0].start(layers[0], m_wanted);
    std::array<std::byte, kWavePacketSize> packet{};
    std::memcpy(packet.data(), first, kWavePacketSize);
    m_contexts.start(context, packet);
}

void WavePacket14V3Decoder::decode(std::byte* out, std::size_t context) {
    auto [models, last] = m_contexts.select(context);
    if (m_layers[0].active())
        decodeWavePacket(m_layers[0].decoder(), models, last.data(), last.data());
    std::memcpy(out, last.data(), kWavePacketSize);
}

} // namespace terratin::io::laz

#pragma once
/// @file
/// Decoder of the WAVEPACKET14 item, version 3: the 29 wave packet bytes of point formats 9
/// and 10 (LAS 1.4 R15, table 14), in one layer, coded as WAVEPACKET13 version 1 codes them
/// (wavepacket_decoder.hpp) with one set of models per scanner channel (channel_contexts.hpp).

#include "channel_contexts.hpp"
#include "layer_stream.hpp"
#include "wavepacket_decoder.hpp"

#include <array>
#include <cstddef>
#include <span>

namespace terratin::io::laz {

class WavePacket14V3Decoder {
public:
    /// `wanted`: whether to decode the layer at all, or repeat the first point's packet.
    explicit WavePacket14V3Decoder(bool wanted);

    [[nodiscard]] static std::size_t layerCount() { return 1; }
    /// A new chunk whose first point has item context `context` and packet `first`, with the
    /// bytes of the item's layer.
    void start(const std::byte* first, std::span<const std::span<const std::byte>> layers,
               std::size_t context);
    void decode(std::byte* out, std::size_t context);
    [[nodiscard]] std::span<const LayerStream> layers() const { return m_layers; }

private:
    bool m_wanted;
    std::array<LayerStream, 1> m_layers;
    ChannelContexts<WavePacketModels, std::array<std::byte, kWavePacketSize>> m_contexts;
};

} // namespace terratin::io::laz

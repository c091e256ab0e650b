#pragma once
/// @file
/// Decoder of the BYTE14 item, version 3: the extra bytes after the standard fields of a LAS
/// 1.4 point record of formats 6-10 (LAS 1.4 R15, 2.6), one layer per byte, each byte coded as
/// its difference (mod 256) from its last value with one adaptive model per byte position and
/// scanner channel (channel_contexts.hpp). Nothing about what the bytes mean is used.

#include "channel_contexts.hpp"
#include "layer_stream.hpp"
#include "range_decoder.hpp"

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace terratin::io::laz {

class Byte14V3Decoder {
public:
    /// `count` extra bytes (at least 1); `wanted`: whether to decode their layers at all, or
    /// repeat the first point's bytes.
    Byte14V3Decoder(std::size_t count, bool wanted);

    [[nodiscard]] std::size_t layerCount() const { return m_layers.size(); }
    /// A new chunk whose first point has item context `context` and extra bytes `first`, with
    /// the bytes of the item's layerCount() layers.
    void start(const std::byte* first, std::span<const std::span<const std::byte>> layers,
               std::size_t context);
    void decode(std::byte* out, std::size_t context);
    [[nodiscard]] std::span<const LayerStream> layers() const { return m_layers; }

private:
    struct Models {
        std::vector<SymbolModel> difference;
        void reset();
    };

    bool m_wanted;
    std::vector<LayerStream> m_layers;
    ChannelContexts<Models, std::vector<std::uint8_t>> m_contexts;
};

} // namespace terratin::io::laz

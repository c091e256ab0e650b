#pragma once
/// @file
/// Decoder of the RGB14 and RGBNIR14 items, version 3: red, green, blue (point formats 7, 8,
/// 10) and, for RGBNIR14, near infrared (formats 8, 10), each a uint16 (LAS 1.4 R15, tables
/// 16-19). The colour is one layer, coded as RGB12 version 2 codes it (rgb_decoder.hpp); the
/// near infrared is a second layer, its low and high byte coded as differences. Both keep their
/// models per scanner channel (channel_contexts.hpp).

#include "channel_contexts.hpp"
#include "layer_stream.hpp"
#include "range_decoder.hpp"
#include "rgb_decoder.hpp"

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

namespace terratin::io::laz {

class Rgb14V3Decoder {
public:
    /// `withNir`: the RGBNIR14 item (8 bytes, two layers), else RGB14 (6 bytes, one layer).
    /// `wanted`: whether to decode the layers at all, or repeat the first point's value.
    Rgb14V3Decoder(bool withNir, bool wanted);

    [[nodiscard]] std::size_t layerCount() const { return m_withNir ? 2 : 1; }
    /// A new chunk whose first point has item context `context` and item bytes `first`, with
    /// the bytes of the item's layerCount() layers.
    void start(const std::byte* first, std::span<const std::span<const std::byte>> layers,
               std::size_t context);
    void decode(std::byte* out, std::size_t context);
    [[nodiscard]] std::span<const LayerStream> layers() const {
        return std::span(m_layers).first(layerCount());
    }

private:
    /// Red, green, blue, near infrared.
    using Value = std::array<std::uint16_t, 4>;
    struct Models {
        ColourModels colour;
        SymbolModel nirChangedBytes{4};
        std::array<SymbolModel, 2> nirByteDifference{SymbolModel(256), SymbolModel(256)};
        void reset();
    };
    /// The uint16 values of the item: 3 or 4.
    [[nodiscard]] std::size_t channelCount() const { return m_withNir ? 4 : 3; }
    [[nodiscard]] std::uint16_t decodeNir(Models& models, std::uint16_t last);

    bool m_withNir;
    bool m_wanted;
    std::array<LayerStream, 2> m_layers;
    ChannelContexts<Models, Value> m_contexts;
};

} // namespace terratin::io::laz

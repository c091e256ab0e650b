/// @file
/// BYTE14 item decoder, version 3 (see byte14_decoder.hpp).

#include "byte14_decoder.hpp"

#include <string>

namespace terratin::io::laz {

namespace {

std::vector<LayerStream> byteLayers(std::size_t count) {
    std::vector<LayerStream> layers;
    layers.reserve(count);
    for (std::size_t i = 0; i < count; ++i)
        layers.emplace_back("extra byte " + std::to_string(i + 1));
    return layers;
}

} // namespace

void Byte14V3Decoder::Models::reset() {
    for (SymbolModel& model : difference)
        model.reset();
}

Byte14V3Decoder::Byte14V3Decoder(std::size_t count, bool wanted)
    : m_wanted(wanted), m_layers(byteLayers(count)), m_contexts([count] {
          auto models = std::make_unique<Models>();
          models->difference.reserve(count);
          for (std::size_t i = 0; i < count; ++i)
              models->difference.emplace_back(256);
          return models;
      }) {}

void Byte14V3Decoder::start(const std::byte* first,
                            std::span<const std::span<const std::byte>> layers,
                            std::size_t context) {
    std::vector<std::uint8_t> value(m_layers.size());
    for (std::size_t i = 0; i < m_layers.size(); ++i) {
        m_layers[i].start(layers[i], m_wanted);
        value[i] = std::to_integer<std::uint8_t>(first[i]);
    }
    m_contexts.start(context, value);
}

void Byte14V3Decoder::decode(std::byte* out, std::size_t context) {
    auto [models, last] = m_contexts.select(context);
    for (std::size_t i = 0; i < m_layers.size(); ++i) {
        if (m_layers[i].active())
            last[i] = static_cast<std::uint8_t>(
                last[i] + m_layers[i].decoder().decodeSymbol(models.difference[i]));
        out[i] = static_cast<std::byte>(last[i]);
    }
}

} // namespace terratin::io::laz

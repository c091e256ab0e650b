/// @file
/// RGB14 and RGBNIR14 item decoder, version 3 (see rgb14_decoder.hpp).

#include "rgb14_decoder.hpp"

#include "laz_bytes.hpp"

namespace terratin::io::laz {

void Rgb14V3Decoder::Models::reset() {
    colour.reset();
    nirChangedBytes.reset();
    for (SymbolModel& model : nirByteDifference)
        model.reset();
}

Rgb14V3Decoder::Rgb14V3Decoder(bool withNir, bool wanted)
    : m_withNir(withNir), m_wanted(wanted), m_layers{LayerStream("rgb"), LayerStream("nir")},
      m_contexts([] { return std::make_unique<Models>(); }) {}

void Rgb14V3Decoder::start(const std::byte* first,
                           std::span<const std::span<const std::byte>> layers,
                           std::size_t context) {
    for (std::size_t i = 0; i < layerCount(); ++i)
        m_layers[i].start(layers[i], m_wanted);
    Value value{};
    for (std::size_t i = 0; i < channelCount(); ++i)
        value[i] = loadLe<std::uint16_t>(first + 2 * i);
    m_contexts.start(context, value);
}

void Rgb14V3Decoder::decode(std::byte* out, std::size_t context) {
    auto [models, last] = m_contexts.select(context);
    if (m_layers[0].active()) {
        const Colour colour =
            decodeColourV2(m_layers[0].decoder(), models.colour, {last[0], last[1], last[2]});
        std::copy(colour.begin(), colour.end(), last.begin());
    }
    if (m_withNir && m_layers[1].active())
        last[3] = decodeNir(models, last[3]);
    for (std::size_t i = 0; i < channelCount(); ++i)
        storeLe(out + 2 * i, last[i]);
}

std::uint16_t Rgb14V3Decoder::decodeNir(Models& models, std::uint16_t last) {
    // Bit 0 of the first symbol: the low byte changed, bit 1: the high byte; each changed
    // byte is its last value plus a coded difference (mod 256).
    RangeDecoder& decoder = m_layers[1].decoder();
    const std::uint32_t changed = decoder.decodeSymbol(models.nirChangedBytes);
    std::uint32_t value = last;
    for (unsigned h = 0; h < 2; ++h) {
        if ((changed & (1u << h)) == 0)
            continue;
        const unsigned shift = 8 * h;
        const std::uint32_t byte =
            (((last >> shift) & 0xFFu) + decoder.decodeSymbol(models.nirByteDifference[h])) & 0xFFu;
        value = (value & ~(0xFFu << shift)) | (byte << shift);
    }
    return static_cast<std::uint16_t>(value);
}

} // namespace terratin::io::laz

/// @file
/// RGB12 item decoders, versions 1 and 2 (see rgb_decoder.hpp).

#include "rgb_decoder.hpp"

#include "laz_bytes.hpp"

#include <algorithm>

namespace terratin::io::laz {

namespace {

std::array<std::uint16_t, 3> loadColour(const std::byte* bytes) {
    return {loadLe<std::uint16_t>(bytes), loadLe<std::uint16_t>(bytes + 2),
            loadLe<std::uint16_t>(bytes + 4)};
}

void storeColour(std::byte* bytes, const std::array<std::uint16_t, 3>& colour) {
    storeLe(bytes, colour[0]);
    storeLe(bytes + 2, colour[1]);
    storeLe(bytes + 4, colour[2]);
}

/// Byte `shift` (0 or 8) of a channel.
int byteOf(std::uint16_t channel, unsigned shift) {
    return (channel >> shift) & 0xFF;
}

/// A predicted byte value kept inside 0..255.
int clampToByte(int value) {
    return std::clamp(value, 0, 255);
}

} // namespace

// ---- version 1 --------------------------------------------------------------------------

Rgb12V1Decoder::Rgb12V1Decoder() : m_changedBytes(64), m_byteValue(8, 6) {}

void Rgb12V1Decoder::start(const std::byte* first) {
    m_last = loadColour(first);
    m_changedBytes.reset();
    m_byteValue.reset();
}

void Rgb12V1Decoder::decode(RangeDecoder& decoder, std::byte* out) {
    // Bit 2c + h of the first symbol: byte h (0 low, 1 high) of channel c changed; each
    // changed byte is predicted from its last value, under its own context 2c + h.
    const std::uint32_t changed = decoder.decodeSymbol(m_changedBytes);
    std::array<std::uint16_t, 3> colour = m_last;
    for (unsigned c = 0; c < 3; ++c) {
        for (unsigned h = 0; h < 2; ++h) {
            const unsigned bit = 2 * c + h;
            if ((changed & (1u << bit)) == 0)
                continue;
            const unsigned shift = 8 * h;
            const auto value = static_cast<std::uint32_t>(
                m_byteValue.decode(decoder, byteOf(m_last[c], shift), bit));
            colour[c] = static_cast<std::uint16_t>((colour[c] & ~(0xFFu << shift)) |
                                                   ((value & 0xFFu) << shift));
        }
    }
    m_last = colour;
    storeColour(out, colour);
}

// ---- version 2 --------------------------------------------------------------------------

namespace {

/// Sets byte `shift` (0 or 8) of a channel to the low 8 bits of `value`.
void setByte(std::uint16_t& channel, unsigned shift, int value) {
    channel = static_cast<std::uint16_t>((channel & ~(0xFFu << shift)) |
                                         ((static_cast<unsigned>(value) & 0xFFu) << shift));
}

/// One channel byte (`shift` 0 low, 8 high) of green and blue, predicted from red's change.
void decodeGreenBlueByte(RangeDecoder& decoder, ColourModels& models, std::uint32_t changed,
                         unsigned shift, const Colour& last, Colour& colour) {
    const unsigned h = shift / 8;
    // Green moves as red did; blue as the average of red's and green's moves (rounded toward
    // zero, as C's division).
    const int redChange = byteOf(colour[0], shift) - byteOf(last[0], shift);
    if (changed & (1u << (2 + h))) {
        const auto step = static_cast<int>(decoder.decodeSymbol(models.byteDifference[2 + h]));
        setByte(colour[1], shift, step + clampToByte(redChange + byteOf(last[1], shift)));
    }
    if (changed & (1u << (4 + h))) {
        const int greenChange = byteOf(colour[1], shift) - byteOf(last[1], shift);
        const int blueChange = (redChange + greenChange) / 2;
        const auto step = static_cast<int>(decoder.decodeSymbol(models.byteDifference[4 + h]));
        setByte(colour[2], shift, step + clampToByte(blueChange + byteOf(last[2], shift)));
    }
}

} // namespace

ColourModels::ColourModels()
    : changedBytes(128), byteDifference{SymbolModel(256), SymbolModel(256), SymbolModel(256),
                                        SymbolModel(256), SymbolModel(256), SymbolModel(256)} {}

void ColourModels::reset() {
    changedBytes.reset();
    for (SymbolModel& model : byteDifference)
        model.reset();
}

Colour decodeColourV2(RangeDecoder& decoder, ColourModels& models, const Colour& last) {
    // Bits of the first symbol: 0 red low, 1 red high, 2 green low, 3 green high, 4 blue
    // low, 5 blue high changed; 6 the colour is not a grey. A changed byte is its last value
    // plus a coded byte difference (mod 256).
    const std::uint32_t changed = decoder.decodeSymbol(models.changedBytes);
    Colour colour = last;
    for (unsigned h = 0; h < 2; ++h) {
        if ((changed & (1u << h)) == 0)
            continue;
        const unsigned shift = 8 * h;
        const auto step = static_cast<int>(decoder.decodeSymbol(models.byteDifference[h]));
        setByte(colour[0], shift, byteOf(last[0], shift) + step);
    }
    if (changed & (1u << 6)) {
        decodeGreenBlueByte(decoder, models, changed, 0, last, colour);
        decodeGreenBlueByte(decoder, models, changed, 8, last, colour);
    } else {
        colour[1] = colour[0];
        colour[2] = colour[0];
    }
    return colour;
}

void Rgb12V2Decoder::start(const std::byte* first) {
    m_last = loadColour(first);
    m_models.reset();
}

void Rgb12V2Decoder::decode(RangeDecoder& decoder, std::byte* out) {
    m_last = decodeColourV2(decoder, m_models, m_last);
    storeColour(out, m_last);
}

} // namespace terratin::io::laz

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

Rgb12V2Decoder::Rgb12V2Decoder()
    : m_changedBytes(128), m_byteDifference{SymbolModel(256), SymbolModel(256), SymbolModel(256),
                                            SymbolModel(256), SymbolModel(256), SymbolModel(256)} {}

void Rgb12V2Decoder::start(const std::byte* first) {
    m_last = loadColour(first);
    m_changedBytes.reset();
    for (SymbolModel& model : m_byteDifference)
        model.reset();
}

void Rgb12V2Decoder::decode(RangeDecoder& decoder, std::byte* out) {
    // Bits of the first symbol: 0 red low, 1 red high, 2 green low, 3 green high, 4 blue
    // low, 5 blue high changed; 6 the colour is not a grey. A changed byte is its last value
    // plus a coded byte difference (mod 256).
    const std::uint32_t changed = decoder.decodeSymbol(m_changedBytes);
    std::array<std::uint16_t, 3> colour = m_last;
    for (unsigned h = 0; h < 2; ++h) {
        if ((changed & (1u << h)) == 0)
            continue;
        const unsigned shift = 8 * h;
        const std::uint32_t step = decoder.decodeSymbol(m_byteDifference[h]);
        const auto value = static_cast<std::uint32_t>(byteOf(m_last[0], shift) + step) & 0xFFu;
        colour[0] = static_cast<std::uint16_t>((colour[0] & ~(0xFFu << shift)) | (value << shift));
    }
    if (changed & (1u << 6)) {
        decodeGreenBlueByte(decoder, changed, 0, colour);
        decodeGreenBlueByte(decoder, changed, 8, colour);
    } else {
        colour[1] = colour[0];
        colour[2] = colour[0];
    }
    m_last = colour;
    storeColour(out, colour);
}

void Rgb12V2Decoder::decodeGreenBlueByte(RangeDecoder& decoder, std::uint32_t changed,
                                         unsigned shift, std::array<std::uint16_t, 3>& colour) {
    const unsigned h = shift / 8;
    const auto setByte = [shift](std::uint16_t& channel, int value) {
        channel = static_cast<std::uint16_t>((channel & ~(0xFFu << shift)) |
                                             ((static_cast<unsigned>(value) & 0xFFu) << shift));
    };
    // Green moves as red did; blue as the average of red's and green's moves (rounded toward
    // zero, as C's division).
    int redChange = byteOf(colour[0], shift) - byteOf(m_last[0], shift);
    if (changed & (1u << (2 + h))) {
        const auto step = static_cast<int>(decoder.decodeSymbol(m_byteDifference[2 + h]));
        setByte(colour[1], step + clampToByte(redChange + byteOf(m_last[1], shift)));
    }
    if (changed & (1u << (4 + h))) {
        const int greenChange = byteOf(colour[1], shift) - byteOf(m_last[1], shift);
        const int blueChange = (redChange + greenChange) / 2;
        const auto step = static_cast<int>(decoder.decodeSymbol(m_byteDifference[4 + h]));
        setByte(colour[2], step + clampToByte(blueChange + byteOf(m_last[2], shift)));
    }
}

} // namespace terratin::io::laz

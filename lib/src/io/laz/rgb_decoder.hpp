#pragma once
/// @file
/// Decoders of the RGB12 item: red, green, blue as three uint16 (point formats 2, 3, 5; LAS
/// 1.4 R15, tables 9-12). Each 16-bit channel is coded as its low and high byte; a first
/// symbol says which of the six bytes changed. Version 2 also says whether the colour is a
/// grey (all channels equal) and predicts green and blue from red's change (Isenburg 2013).

#include "integer_decoder.hpp"
#include "range_decoder.hpp"

#include <array>
#include <cstddef>
#include <cstdint>

namespace terratin::io::laz {

class Rgb12V1Decoder {
public:
    Rgb12V1Decoder();
    void start(const std::byte* first);
    void decode(RangeDecoder& decoder, std::byte* out);

private:
    std::array<std::uint16_t, 3> m_last{};
    SymbolModel m_changedBytes;
    IntegerDecoder m_byteValue;
};

class Rgb12V2Decoder {
public:
    Rgb12V2Decoder();
    void start(const std::byte* first);
    void decode(RangeDecoder& decoder, std::byte* out);

private:
    /// One channel byte (`shift` 0 low, 8 high) of green and blue, predicted from red's.
    void decodeGreenBlueByte(RangeDecoder& decoder, std::uint32_t changed, unsigned shift,
                             std::array<std::uint16_t, 3>& colour);

    std::array<std::uint16_t, 3> m_last{};
    SymbolModel m_changedBytes;
    /// One model per byte: red low, red high, green low, green high, blue low, blue high.
    std::array<SymbolModel, 6> m_byteDifference;
};

} // namespace terratin::io::laz

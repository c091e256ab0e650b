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

/// Red, green, blue.
using Colour = std::array<std::uint16_t, 3>;

/// The models of version 2's colour coding. RGB14 and RGBNIR14 (version 3) code colours the
/// same way, with one set of these per scanner channel.
struct ColourModels {
    ColourModels();
    /// Back to their initial state, as at the start of every chunk.
    void reset();

    SymbolModel changedBytes;
    /// One model per byte: red low, red high, green low, green high, blue low, blue high.
    std::array<SymbolModel, 6> byteDifference;
};

/// The colour that follows `last`, as version 2 codes it.
[[nodiscard]] Colour decodeColourV2(RangeDecoder& decoder, ColourModels& models,
                                    const Colour& last);

class Rgb12V2Decoder {
public:
    void start(const std::byte* first);
    void decode(RangeDecoder& decoder, std::byte* out);

private:
    Colour m_last{};
    ColourModels m_models;
};

} // namespace terratin::io::laz

#pragma once
/// @file
/// LASzip's integer "compressor", decoding side: a value is stored as the correction to a
/// prediction. The correction's magnitude class k (its bit length) is an adaptive symbol,
/// chosen among one model per context; the position inside class k follows, its high bits
/// through a per-class symbol model and, for wide classes, its low bits raw
/// (Isenburg 2013). Values wrap around in `bits` bits, so
/// a correction never needs more than that many.

#include "range_decoder.hpp"

#include <cstdint>
#include <vector>

namespace terratin::io::laz {

class IntegerDecoder {
public:
    /// Values of `bits` bits (1-31; 0 or 32 and more: full 32-bit wrap-around), `contexts`
    /// separate models for the magnitude class, classes wider than `highBits` sending their
    /// low bits raw. A non-zero `range` instead limits the values to [0, range).
    explicit IntegerDecoder(std::uint32_t bits, std::uint32_t contexts = 1,
                            std::uint32_t highBits = 8, std::uint32_t range = 0);

    /// Every model back to its initial state, as at the start of every chunk.
    void reset();

    /// The value predicted as `prediction`, under model `context` (< contexts).
    [[nodiscard]] std::int32_t decode(RangeDecoder& decoder, std::int32_t prediction,
                                      std::uint32_t context = 0) {
        const auto corrected = static_cast<std::uint32_t>(prediction) +
                               static_cast<std::uint32_t>(decodeCorrection(decoder, context));
        std::uint32_t value = corrected;
        if (static_cast<std::int32_t>(corrected) < 0)
            value = corrected + m_range;
        else if (corrected >= m_range)
            value = corrected - m_range;
        return static_cast<std::int32_t>(value);
    }

    /// The magnitude class of the last correction decoded; the point decoders use it to pick
    /// the context of the next coordinate.
    [[nodiscard]] std::uint32_t lastClass() const { return m_lastClass; }

private:
    [[nodiscard]] std::int32_t decodeCorrection(RangeDecoder& decoder, std::uint32_t context);

    std::uint32_t m_correctionBits = 32;
    /// 2^bits, or 0 for full 32-bit wrap-around (the range checks then never fire).
    std::uint32_t m_range = 0;
    std::int32_t m_smallestCorrection = 0;
    std::uint32_t m_highBits = 8;
    std::uint32_t m_lastClass = 0;
    std::vector<SymbolModel> m_classModels;
    /// Class 0 holds the corrections 0 and 1, told apart by one adaptive bit.
    BitModel m_zeroOrOne;
    /// Entry k - 1: the position inside class k (all of it, or its top highBits bits).
    std::vector<SymbolModel> m_positionModels;
};

} // namespace terratin::io::laz

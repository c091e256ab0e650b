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

/// What both sides of the integer compressor build alike from the same arguments, so that
/// they stay in step: the width of a correction, the range values wrap in, and the adaptive
/// models of the corrections' classes and positions.
struct IntegerModels {
    /// Values of `bits` bits (1-31; 0 or 32 and more: full 32-bit wrap-around), `contexts`
    /// separate models for the magnitude class, classes wider than `highBits` sending their
    /// low bits raw. A non-zero `range` instead limits the values to [0, range).
    IntegerModels(std::uint32_t bits, std::uint32_t contexts, std::uint32_t highBits,
                  std::uint32_t range);

    /// Every model back to its initial state, as at the start of every chunk.
    void reset();

    /// The widest correction's class (its bit length).
    std::uint32_t correctionBits = 32;
    /// The values lie in [0, valueRange): 2^bits or the range given, or 0 for full 32-bit
    /// wrap-around (the range checks then never fire).
    std::uint32_t valueRange = 0;
    /// The most negative correction: corrections lie in [smallest, smallest + valueRange).
    std::int32_t smallestCorrection = 0;
    /// `highBits`: the most bits of a position coded through its model, the rest raw.
    std::uint32_t modelledPositionBits = 8;
    /// One per context: the class (0 .. correctionBits) of the next correction.
    std::vector<SymbolModel> classModels;
    /// Class 0 holds the corrections 0 and 1, told apart by one adaptive bit.
    BitModel zeroOrOne;
    /// Entry k - 1: the position inside class k (all of it, or its top modelledPositionBits).
    std::vector<SymbolModel> positionModels;
};

/// Decodes the values of one integer compressor, correction by correction.
class IntegerDecoder {
public:
    /// The arguments as IntegerModels takes them.
    explicit IntegerDecoder(std::uint32_t bits, std::uint32_t contexts = 1,
                            std::uint32_t highBits = 8, std::uint32_t range = 0)
        : m_models(bits, contexts, highBits, range) {}

    /// Every model back to its initial state, as at the start of every chunk.
    void reset();

    /// The value predicted as `prediction`, under model `context` (< contexts).
    [[nodiscard]] std::int32_t decode(RangeDecoder& decoder, std::int32_t prediction,
                                      std::uint32_t context = 0) {
        const auto corrected = static_cast<std::uint32_t>(prediction) +
                               static_cast<std::uint32_t>(decodeCorrection(decoder, context));
        std::uint32_t value = corrected;
        if (static_cast<std::int32_t>(corrected) < 0)
            value = corrected + m_models.valueRange;
        else if (corrected >= m_models.valueRange)
            value = corrected - m_models.valueRange;
        return static_cast<std::int32_t>(value);
    }

    /// The magnitude class of the last correction decoded; the point decoders use it to pick
    /// the context of the next coordinate.
    [[nodiscard]] std::uint32_t lastClass() const { return m_lastClass; }

private:
    [[nodiscard]] std::int32_t decodeCorrection(RangeDecoder& decoder, std::uint32_t context);

    IntegerModels m_models;
    std::uint32_t m_lastClass = 0;
};

} // namespace terratin::io::laz

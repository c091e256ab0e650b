/// @file
/// The corrector of LASzip's integer compressor (see integer_decoder.hpp).

#include "integer_decoder.hpp"

#include <algorithm>
#include <limits>

namespace terratin::io::laz {

IntegerModels::IntegerModels(std::uint32_t bits, std::uint32_t contexts, std::uint32_t highBits,
                             std::uint32_t range)
    : modelledPositionBits(highBits) {
    if (range != 0) {
        // As many bits as the range needs, one fewer when it is a power of two.
        correctionBits = 0;
        for (std::uint32_t rest = range; rest != 0; rest >>= 1)
            ++correctionBits;
        if (range == 1u << (correctionBits - 1))
            --correctionBits;
        valueRange = range;
        smallestCorrection = -static_cast<std::int32_t>(range / 2);
    } else if (bits != 0 && bits < 32) {
        correctionBits = bits;
        valueRange = 1u << bits;
        smallestCorrection = -static_cast<std::int32_t>(valueRange / 2);
    } else {
        correctionBits = 32;
        valueRange = 0;
        smallestCorrection = std::numeric_limits<std::int32_t>::min();
    }
    classModels.reserve(contexts);
    for (std::uint32_t c = 0; c < contexts; ++c)
        classModels.emplace_back(correctionBits + 1);
    positionModels.reserve(correctionBits);
    for (std::uint32_t k = 1; k <= correctionBits; ++k)
        positionModels.emplace_back(1u << std::min(k, modelledPositionBits));
}

void IntegerModels::reset() {
    for (SymbolModel& model : classModels)
        model.reset();
    zeroOrOne.reset();
    for (SymbolModel& model : positionModels)
        model.reset();
}

void IntegerDecoder::reset() {
    m_models.reset();
    m_lastClass = 0;
}

std::int32_t IntegerDecoder::decodeCorrection(RangeDecoder& decoder, std::uint32_t context) {
    const std::uint32_t k = decoder.decodeSymbol(m_models.classModels[context]);
    m_lastClass = k;
    if (k == 0)
        return static_cast<std::int32_t>(decoder.decodeBit(m_models.zeroOrOne));
    // Class 32 exists only for 32-bit values: the one correction -2^31 that has no other.
    if (k >= 32)
        return m_models.smallestCorrection;
    std::uint32_t position = decoder.decodeSymbol(m_models.positionModels[k - 1]);
    if (k > m_models.modelledPositionBits) {
        const std::uint32_t lowBits = k - m_models.modelledPositionBits;
        position = (position << lowBits) | decoder.readBits(lowBits);
    }
    // Class k holds the 2^k corrections -(2^k - 1) .. -2^(k-1) and 2^(k-1) + 1 .. 2^k, in
    // that order; positions from 2^(k-1) on are the positive half.
    if (position >= 1u << (k - 1))
        return static_cast<std::int32_t>(position + 1);
    return static_cast<std::int32_t>(position - ((1u << k) - 1));
}

} // namespace terratin::io::laz

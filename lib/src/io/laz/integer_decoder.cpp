/// @file
/// The corrector of LASzip's integer compressor (see integer_decoder.hpp).

#include "integer_decoder.hpp"

#include <limits>

namespace terratin::io::laz {

IntegerDecoder::IntegerDecoder(std::uint32_t bits, std::uint32_t contexts, std::uint32_t highBits,
                               std::uint32_t range)
    : m_highBits(highBits) {
    if (range != 0) {
        // As many bits as the range needs, one fewer when it is a power of two.
        m_correctionBits = 0;
        for (std::uint32_t rest = range; rest != 0; rest >>= 1)
            ++m_correctionBits;
        if (range == 1u << (m_correctionBits - 1))
            --m_correctionBits;
        m_range = range;
        m_smallestCorrection = -static_cast<std::int32_t>(range / 2);
    } else if (bits != 0 && bits < 32) {
        m_correctionBits = bits;
        m_range = 1u << bits;
        m_smallestCorrection = -static_cast<std::int32_t>(m_range / 2);
    } else {
        m_correctionBits = 32;
        m_range = 0;
        m_smallestCorrection = std::numeric_limits<std::int32_t>::min();
    }
    m_classModels.reserve(contexts);
    for (std::uint32_t c = 0; c < contexts; ++c)
        m_classModels.emplace_back(m_correctionBits + 1);
    m_positionModels.reserve(m_correctionBits);
    for (std::uint32_t k = 1; k <= m_correctionBits; ++k)
        m_positionModels.emplace_back(1u << (k <= m_highBits ? k : m_highBits));
}

void IntegerDecoder::reset() {
    for (SymbolModel& model : m_classModels)
        model.reset();
    m_zeroOrOne.reset();
    for (SymbolModel& model : m_positionModels)
        model.reset();
    m_lastClass = 0;
}

std::int32_t IntegerDecoder::decodeCorrection(RangeDecoder& decoder, std::uint32_t context) {
    const std::uint32_t k = decoder.decodeSymbol(m_classModels[context]);
    m_lastClass = k;
    if (k == 0)
        return static_cast<std::int32_t>(decoder.decodeBit(m_zeroOrOne));
    // Class 32 exists only for 32-bit values: the one correction -2^31 that has no other.
    if (k >= 32)
        return m_smallestCorrection;
    std::uint32_t position = decoder.decodeSymbol(m_positionModels[k - 1]);
    if (k > m_highBits) {
        const std::uint32_t lowBits = k - m_highBits;
        position = (position << lowBits) | decoder.readBits(lowBits);
    }
    // Class k holds the 2^k corrections -(2^k - 1) .. -2^(k-1) and 2^(k-1) + 1 .. 2^k, in
    // that order; positions from 2^(k-1) on are the positive half.
    if (position >= 1u << (k - 1))
        return static_cast<std::int32_t>(position + 1);
    return static_cast<std::int32_t>(position - ((1u << k) - 1));
}

} // namespace terratin::io::laz

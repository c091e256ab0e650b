/// @file
/// Model bookkeeping of the LAZ range decoder (see range_decoder.hpp). The refresh rules
/// below fix when and how counts become probabilities; the encoder adapts these same models,
/// which is what keeps both sides in step (FastAC, Said 2004; LASzip, Isenburg 2013).

#include "range_decoder.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace terratin::io::laz {

namespace {
/// A symbol model's counts total at most 2^15 before they are halved.
constexpr std::uint32_t kSymbolCountLimit = 1u << 15;
/// A bit model's counts total at most 2^13 before they are halved.
constexpr std::uint32_t kBitCountLimit = 1u << 13;
constexpr std::uint32_t kMaxSymbols = 1u << 11;
/// Alphabets up to this size are searched by bisection alone.
constexpr std::uint32_t kLargestUntabledAlphabet = 16;
} // namespace

void BitModel::reset() {
    m_zeroCount = 1;
    m_totalCount = 2;
    m_zeroProbability = 1u << (kProbabilityBits - 1);
    m_refreshCycle = 4;
    m_untilRefresh = 4;
}

void BitModel::refresh() {
    m_totalCount += m_refreshCycle;
    if (m_totalCount > kBitCountLimit) {
        m_totalCount = (m_totalCount + 1) >> 1;
        m_zeroCount = (m_zeroCount + 1) >> 1;
        // A probability of exactly 1 would leave the other bit no interval.
        if (m_zeroCount == m_totalCount)
            ++m_totalCount;
    }
    const std::uint32_t scale = 0x80000000u / m_totalCount;
    m_zeroProbability = (m_zeroCount * scale) >> (31 - kProbabilityBits);
    m_refreshCycle = std::min<std::uint32_t>((5 * m_refreshCycle) >> 2, 64);
    m_untilRefresh = m_refreshCycle;
}

SymbolModel::SymbolModel(std::uint32_t symbols) : m_symbols(symbols) {
    if (symbols < 2 || symbols > kMaxSymbols)
        throw std::invalid_argument("SymbolModel: " + std::to_string(symbols) +
                                    " symbols, outside 2..2048");
    if (symbols > kLargestUntabledAlphabet) {
        // The smallest power of two, at least 8, that is no less than a quarter of the
        // alphabet: a handful of symbols per lookup slot.
        std::uint32_t lookupBits = 3;
        while (symbols > (1u << (lookupBits + 2)))
            ++lookupBits;
        m_lookupSize = 1u << lookupBits;
        m_lookupShift = kProbabilityBits - lookupBits;
    }
    const std::size_t words = 2 * std::size_t{symbols} + (m_lookupSize ? m_lookupSize + 2 : 0);
    m_storage = std::make_unique<std::uint32_t[]>(words);
    m_cumulative = m_storage.get();
    m_counts = m_cumulative + symbols;
    m_lookup = m_lookupSize ? m_counts + symbols : nullptr;
    reset();
}

void SymbolModel::reset() {
    std::fill(m_counts, m_counts + m_symbols, 1u);
    m_totalCount = 0;
    m_refreshCycle = m_symbols;
    refresh();
    m_refreshCycle = (m_symbols + 6) >> 1;
    m_untilRefresh = m_refreshCycle;
}

void SymbolModel::refresh() {
    m_totalCount += m_refreshCycle;
    if (m_totalCount > kSymbolCountLimit) {
        m_totalCount = 0;
        for (std::uint32_t s = 0; s < m_symbols; ++s) {
            m_counts[s] = (m_counts[s] + 1) >> 1;
            m_totalCount += m_counts[s];
        }
    }
    const std::uint32_t scale = 0x80000000u / m_totalCount;
    std::uint32_t below = 0;
    for (std::uint32_t s = 0; s < m_symbols; ++s) {
        m_cumulative[s] = (scale * below) >> (31 - kProbabilityBits);
        below += m_counts[s];
    }
    if (m_lookupSize != 0)
        rebuildLookup();
    m_refreshCycle = std::min((5 * m_refreshCycle) >> 2, (m_symbols + 6) << 3);
    m_untilRefresh = m_refreshCycle;
}

void SymbolModel::rebuildLookup() {
    // Slot j holds the last symbol whose interval starts below j << shift: the first
    // candidate for a value in slot j, while slot j + 1 bounds the search from above.
    std::uint32_t symbol = 0;
    m_lookup[0] = 0;
    for (std::uint32_t slot = 1; slot <= m_lookupSize + 1; ++slot) {
        while (symbol + 1 < m_symbols && (m_cumulative[symbol + 1] >> m_lookupShift) < slot)
            ++symbol;
        m_lookup[slot] = symbol;
    }
}

void RangeDecoder::start(const std::byte* begin, const std::byte* end) {
    m_begin = begin;
    m_next = begin;
    m_end = end;
    m_bytesPastEnd = 0;
    m_corrupt = false;
    m_length = 0xFFFFFFFFu;
    m_value = 0;
    for (int i = 0; i < 4; ++i)
        m_value = (m_value << 8) | nextByte();
}

} // namespace terratin::io::laz

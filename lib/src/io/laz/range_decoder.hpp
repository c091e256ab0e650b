#pragma once
/// @file
/// The entropy decoder of LAZ: a 32-bit range (arithmetic) decoder with adaptive bit and
/// symbol models. LASzip uses A. Said's fast arithmetic coder (FastAC; Said, "Introduction to
/// arithmetic coding - theory and practice", HP Labs HPL-2004-76) with counts that are turned
/// into probabilities only every so many symbols (Isenburg, "LASzip: lossless compression of
/// LiDAR data", 2013). A decoder must reproduce the encoder's model arithmetic bit
/// for bit, so every constant below is part of the format.
///
/// The decoder reads a bounded byte range; a read past its end yields zeros and is counted,
/// and impossible raw values mark the stream corrupt, so a damaged chunk decodes to garbage
/// that the caller rejects (overran(), corrupt()) instead of reading outside the range.

#include <cstddef>
#include <cstdint>
#include <memory>

namespace terratin::io::laz {

/// The interval length is kept in [2^24, 2^32): below 2^24 another byte is shifted in.
inline constexpr std::uint32_t kRenormaliseBelow = 0x01000000u;

/// At most this many raw bits are coded in one step, so that the interval keeps at least 5 bits
/// of length; wider fields are split into their low 16 bits and the rest.
inline constexpr std::uint32_t kMostRawBitsInOneStep = 19;

/// A part of the coder's current interval: its start, as an offset from the interval's, and
/// its length.
struct Subinterval {
    std::uint32_t low = 0;
    std::uint32_t length = 0;
};

/// An adaptive model of one binary decision. The probability of a 0 is held in 13-bit fixed
/// point and recomputed from the counts after 4 bits, then after ever longer runs (x 5/4, at
/// most 64); counts are halved when they pass 2^13. The decoder and the encoder both adapt it
/// through update(), which is what keeps them in step.
class BitModel {
public:
    BitModel() { reset(); }
    /// Back to equal odds, as at the start of every chunk.
    void reset();

    /// The length of the part of an interval of `length` that a 0 takes, at its start; a 1
    /// takes the rest.
    [[nodiscard]] std::uint32_t zeroLength(std::uint32_t length) const {
        return m_zeroProbability * (length >> kProbabilityBits);
    }
    /// Counts `bit` (0, or anything else for 1) once coded, and refreshes the probability
    /// when due.
    void update(std::uint32_t bit) {
        if (bit == 0)
            ++m_zeroCount;
        if (--m_untilRefresh == 0)
            refresh();
    }

private:
    static constexpr std::uint32_t kProbabilityBits = 13;
    void refresh();

    std::uint32_t m_zeroProbability = 0;
    std::uint32_t m_zeroCount = 0;
    std::uint32_t m_totalCount = 0;
    std::uint32_t m_refreshCycle = 0;
    std::uint32_t m_untilRefresh = 0;
};

/// An adaptive model of an alphabet of 2 to 2048 symbols: per-symbol counts, and the
/// cumulative distribution in 15-bit fixed point recomputed from them after (n + 6) / 2
/// symbols, then after ever longer runs (x 5/4, at most 8 (n + 6)); counts are halved when
/// their total passes 2^15. Alphabets of more than 16 symbols also keep a small lookup table
/// that narrows the decoder's search for a symbol to a few entries. The decoder and the
/// encoder both adapt it through update(), which is what keeps them in step.
class SymbolModel {
public:
    /// Precondition: 2 <= symbols <= 2048 (checked; std::invalid_argument otherwise).
    explicit SymbolModel(std::uint32_t symbols);
    SymbolModel(SymbolModel&&) noexcept = default;
    SymbolModel& operator=(SymbolModel&&) noexcept = default;
    SymbolModel(const SymbolModel&) = delete;
    SymbolModel& operator=(const SymbolModel&) = delete;
    ~SymbolModel() = default;

    /// Back to equal counts, as at the start of every chunk.
    void reset();
    [[nodiscard]] std::uint32_t symbols() const { return m_symbols; }

    /// The part of an interval of `length` that `symbol` takes. Precondition:
    /// symbol < symbols().
    [[nodiscard]] Subinterval subinterval(std::uint32_t symbol, std::uint32_t length) const;
    /// The symbol whose part of an interval of `length` holds `offset` (< length); for a larger
    /// offset, which only a corrupt stream has, still one of the alphabet. O(log symbols).
    [[nodiscard]] std::uint32_t symbolAt(std::uint32_t offset, std::uint32_t length) const;
    /// Counts `symbol` once coded, and refreshes the distribution when due. Precondition:
    /// symbol < symbols().
    void update(std::uint32_t symbol) {
        ++m_counts[symbol];
        if (--m_untilRefresh == 0)
            refresh();
    }

private:
    static constexpr std::uint32_t kProbabilityBits = 15;
    void refresh();
    void rebuildLookup();

    std::uint32_t m_symbols = 0;
    std::uint32_t m_lookupShift = 0;
    std::uint32_t m_lookupSize = 0; ///< 0: no lookup table (small alphabet)
    std::uint32_t m_totalCount = 0;
    std::uint32_t m_refreshCycle = 0;
    std::uint32_t m_untilRefresh = 0;
    /// One allocation: cumulative distribution [symbols], counts [symbols], lookup [size + 2].
    std::unique_ptr<std::uint32_t[]> m_storage;
    std::uint32_t* m_cumulative = nullptr;
    std::uint32_t* m_counts = nullptr;
    std::uint32_t* m_lookup = nullptr;
};

/// Decodes one arithmetic-coded stream held in memory.
class RangeDecoder {
public:
    /// Starts decoding the stream at [begin, end): the first four bytes are the initial code
    /// value, most significant first.
    void start(const std::byte* begin, const std::byte* end);

    [[nodiscard]] std::uint32_t decodeBit(BitModel& model);
    [[nodiscard]] std::uint32_t decodeSymbol(SymbolModel& model);
    /// `count` bits (1 to 32) stored without a model, in equal-probability steps.
    [[nodiscard]] std::uint32_t readBits(std::uint32_t count);
    [[nodiscard]] std::uint32_t readShort() { return readBits(16); }
    /// 32 bits: the low 16 first, then the high 16.
    [[nodiscard]] std::uint32_t readInt();
    /// 64 bits: the low 32 first, then the high 32.
    [[nodiscard]] std::uint64_t readInt64();

    /// Bytes taken from the stream so far, counting those asked for past its end.
    [[nodiscard]] std::size_t consumed() const {
        return static_cast<std::size_t>(m_next - m_begin) + m_bytesPastEnd;
    }
    /// Whether the decoder wanted bytes beyond the end of its range (truncated stream).
    [[nodiscard]] bool overran() const { return m_bytesPastEnd != 0; }
    /// Whether a raw value came out of range (impossible in a stream an encoder wrote).
    [[nodiscard]] bool corrupt() const { return m_corrupt; }
    /// For the item decoders: a decoded value no writer could have produced.
    void markCorrupt() { m_corrupt = true; }

private:
    std::uint32_t nextByte() {
        if (m_next != m_end)
            return static_cast<std::uint32_t>(*m_next++);
        ++m_bytesPastEnd;
        return 0;
    }
    void renormalise() {
        do {
            m_value = (m_value << 8) | nextByte();
            m_length <<= 8;
        } while (m_length < kRenormaliseBelow);
    }
    [[nodiscard]] std::uint32_t readFewBits(std::uint32_t count);

    const std::byte* m_begin = nullptr;
    const std::byte* m_next = nullptr;
    const std::byte* m_end = nullptr;
    std::size_t m_bytesPastEnd = 0;
    bool m_corrupt = false;
    /// The code value's offset inside the current interval, and the interval's length.
    std::uint32_t m_value = 0;
    std::uint32_t m_length = 0;
};

inline Subinterval SymbolModel::subinterval(std::uint32_t symbol, std::uint32_t length) const {
    const std::uint32_t unit = length >> kProbabilityBits;
    const std::uint32_t low = m_cumulative[symbol] * unit;
    // The last symbol's part runs to the end of the interval, rounding included.
    const std::uint32_t high = symbol + 1 == m_symbols ? length : m_cumulative[symbol + 1] * unit;
    return {low, high - low};
}

inline std::uint32_t SymbolModel::symbolAt(std::uint32_t offset, std::uint32_t length) const {
    const std::uint32_t unit = length >> kProbabilityBits;
    // The symbol s is the last one whose part starts at or below the offset:
    // cumulative[s] * unit <= offset < cumulative[s + 1] * unit.
    std::uint32_t symbol = 0;
    std::uint32_t above = m_symbols;
    if (m_lookupSize != 0) {
        const std::uint32_t scaled = offset / unit;
        std::uint32_t slot = scaled >> m_lookupShift;
        if (slot > m_lookupSize) // only a corrupt stream gets here
            slot = m_lookupSize;
        symbol = m_lookup[slot];
        above = m_lookup[slot + 1] + 1;
        while (above > symbol + 1) {
            const std::uint32_t middle = (symbol + above) >> 1;
            if (m_cumulative[middle] > scaled)
                above = middle;
            else
                symbol = middle;
        }
    } else {
        while (above > symbol + 1) {
            const std::uint32_t middle = (symbol + above) >> 1;
            if (m_cumulative[middle] * unit > offset)
                above = middle;
            else
                symbol = middle;
        }
    }
    return symbol;
}

inline std::uint32_t RangeDecoder::decodeBit(BitModel& model) {
    const std::uint32_t split = model.zeroLength(m_length);
    std::uint32_t bit = 0;
    if (m_value < split) {
        m_length = split;
    } else {
        bit = 1;
        m_value -= split;
        m_length -= split;
    }
    if (m_length < kRenormaliseBelow)
        renormalise();
    model.update(bit);
    return bit;
}

inline std::uint32_t RangeDecoder::decodeSymbol(SymbolModel& model) {
    const std::uint32_t symbol = model.symbolAt(m_value, m_length);
    const Subinterval part = model.subinterval(symbol, m_length);
    m_value -= part.low;
    m_length = part.length;
    if (m_length < kRenormaliseBelow)
        renormalise();
    model.update(symbol);
    return symbol;
}

inline std::uint32_t RangeDecoder::readFewBits(std::uint32_t count) {
    m_length >>= count;
    std::uint32_t bits = m_value / m_length;
    m_value -= bits * m_length;
    if (m_length < kRenormaliseBelow)
        renormalise();
    if (bits >> count != 0) {
        m_corrupt = true;
        bits &= (1u << count) - 1;
    }
    return bits;
}

inline std::uint32_t RangeDecoder::readBits(std::uint32_t count) {
    if (count > kMostRawBitsInOneStep) {
        const std::uint32_t low = readFewBits(16);
        return (readBits(count - 16) << 16) | low;
    }
    return readFewBits(count);
}

inline std::uint32_t RangeDecoder::readInt() {
    const std::uint32_t low = readFewBits(16);
    return (readFewBits(16) << 16) | low;
}

inline std::uint64_t RangeDecoder::readInt64() {
    const std::uint64_t low = readInt();
    return (static_cast<std::uint64_t>(readInt()) << 32) | low;
}

} // namespace terratin::io::laz

#pragma once
/// @file
/// The encoding side of LAZ's entropy coder, written as the exact inverse of the project's
/// decoder (lib/src/io/laz/range_decoder.hpp, integer_decoder.hpp): a 32-bit range encoder
/// with the same adaptive bit and symbol models, LASzip's integer compressor on top of it,
/// and the chunk table's coded entries. terratin-lazrepeat needs it to write the chunk table
/// of a repeated file; the tests need it to feed the decoder streams of known content.
///
/// Both sides must adapt their models identically, symbol for symbol, so every constant and
/// refresh rule below is the decoder's (FastAC, Said 2004, as LASzip adapts it, Isenburg
/// 2013). The decoder keeps its models' state private, so the encoder keeps its own copies.

#include "chunk_table.hpp"

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace terratin::lazrepeat {

/// An adaptive model of one binary decision, encoder side: the decoder's BitModel rules.
class EncoderBitModel {
public:
    EncoderBitModel() { reset(); }
    /// Back to equal odds, as at the start of every chunk.
    void reset();

private:
    friend class RangeEncoder;
    void refresh();

    std::uint32_t m_zeroProbability = 0;
    std::uint32_t m_zeroCount = 0;
    std::uint32_t m_totalCount = 0;
    std::uint32_t m_refreshCycle = 0;
    std::uint32_t m_untilRefresh = 0;
};

/// An adaptive model of 2 to 2048 symbols, encoder side: the decoder's SymbolModel counts and
/// cumulative distribution; the encoder needs no lookup table, it knows its symbol.
class EncoderSymbolModel {
public:
    /// Precondition: 2 <= symbols <= 2048 (checked; std::invalid_argument otherwise).
    explicit EncoderSymbolModel(std::uint32_t symbols);
    /// Back to equal counts, as at the start of every chunk.
    void reset();
    [[nodiscard]] std::uint32_t symbols() const {
        return static_cast<std::uint32_t>(m_counts.size());
    }

private:
    friend class RangeEncoder;
    void refresh();

    std::uint32_t m_totalCount = 0;
    std::uint32_t m_refreshCycle = 0;
    std::uint32_t m_untilRefresh = 0;
    std::vector<std::uint32_t> m_counts;
    std::vector<std::uint32_t> m_cumulative;
};

/// Encodes one arithmetic-coded stream into memory; finish() returns it. The decoder, started
/// on exactly those bytes, reads every value back without asking for a byte past their end.
class RangeEncoder {
public:
    void encodeBit(EncoderBitModel& model, std::uint32_t bit);
    /// Precondition: symbol < model.symbols() (checked; std::invalid_argument otherwise).
    void encodeSymbol(EncoderSymbolModel& model, std::uint32_t symbol);
    /// The low `count` bits (1 to 32) of `value` without a model; RangeDecoder::readBits.
    void writeBits(std::uint32_t count, std::uint32_t value);
    void writeShort(std::uint32_t value) { writeBits(16, value & 0xFFFFu); }
    /// 32 bits: the low 16 first, then the high 16 (RangeDecoder::readInt).
    void writeInt(std::uint32_t value);
    /// 64 bits: the low 32 first, then the high 32 (RangeDecoder::readInt64).
    void writeInt64(std::uint64_t value);

    /// Ends the stream and hands over its bytes; the encoder starts afresh after it.
    [[nodiscard]] std::vector<std::byte> finish();

private:
    void writeFewBits(std::uint32_t count, std::uint32_t value);
    /// base += amount, carried into the bytes already out when the 32-bit base wraps.
    void advanceBase(std::uint32_t amount);
    void propagateCarry();
    void renormalise();

    std::uint32_t m_base = 0;
    std::uint32_t m_length = 0xFFFFFFFFu;
    std::vector<std::byte> m_bytes;
};

/// LASzip's integer compressor, encoder side: the inverse of IntegerDecoder built with the
/// same arguments (same meaning of `bits`, `contexts`, `highBits` and `range`).
class IntegerEncoder {
public:
    explicit IntegerEncoder(std::uint32_t bits, std::uint32_t contexts = 1,
                            std::uint32_t highBits = 8, std::uint32_t range = 0);

    /// Every model back to its initial state, as at the start of every chunk.
    void reset();

    /// Stores `value` as its correction to `prediction`, under model `context` (< contexts;
    /// checked). For a `bits`-bit or `range` encoder both lie in [0, 2^bits) or [0, range).
    void encode(RangeEncoder& encoder, std::int32_t prediction, std::int32_t value,
                std::uint32_t context = 0);

    /// The magnitude class of the last correction encoded (IntegerDecoder::lastClass).
    [[nodiscard]] std::uint32_t lastClass() const { return m_lastClass; }

private:
    void encodeCorrection(RangeEncoder& encoder, std::int32_t correction, std::uint32_t context);

    std::uint32_t m_correctionBits = 32;
    /// 2^bits, or 0 for full 32-bit wrap-around (no folding needed).
    std::uint32_t m_range = 0;
    std::int32_t m_smallestCorrection = 0;
    std::uint32_t m_highBits = 8;
    std::uint32_t m_lastClass = 0;
    std::vector<EncoderSymbolModel> m_classModels;
    EncoderBitModel m_zeroOrOne;
    std::vector<EncoderSymbolModel> m_positionModels;
};

/// The arithmetic-coded part of a chunk table (what follows its version and count), the
/// inverse of io::laz::decodeChunkTableEntries: per entry its point count (context 0; only
/// for variable chunks) and byte count (context 1), each predicted from the previous entry's,
/// the first from 0. Empty for no entries, as LASzip writes it.
[[nodiscard]] std::vector<std::byte>
encodeChunkTableEntries(std::span<const io::laz::ChunkTableEntry> entries, bool variableChunks);

/// A whole chunk table: u32 version 0, u32 entry count, then the coded entries.
[[nodiscard]] std::vector<std::byte>
encodeChunkTable(std::span<const io::laz::ChunkTableEntry> entries, bool variableChunks);

} // namespace terratin::lazrepeat

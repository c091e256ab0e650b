#pragma once
/// @file
/// The encoding side of LAZ's entropy coder, written as the exact inverse of the project's
/// decoder (lib/src/io/laz/range_decoder.hpp, integer_decoder.hpp): a 32-bit range encoder,
/// LASzip's integer compressor on top of it, and the chunk table's coded entries.
/// terratin-lazrepeat needs it to write the chunk table of a repeated file; the tests need it
/// to feed the decoder streams of known content.
///
/// Both sides must adapt their models identically, symbol for symbol (FastAC, Said 2004, as
/// LASzip adapts it, Isenburg 2013), so the encoder codes with the decoder's own models
/// (io::laz::BitModel, SymbolModel, IntegerModels) rather than copies of their rules.

#include "chunk_table.hpp"
#include "integer_decoder.hpp"
#include "range_decoder.hpp"

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace terratin::lazrepeat {

/// Encodes one arithmetic-coded stream into memory; finish() returns it. The decoder, started
/// on exactly those bytes, reads every value back without asking for a byte past their end.
class RangeEncoder {
public:
    /// `bit`: 0, or anything else for 1 (as BitModel::update counts it).
    void encodeBit(io::laz::BitModel& model, std::uint32_t bit);
    /// Precondition: symbol < model.symbols() (checked; std::invalid_argument otherwise).
    void encodeSymbol(io::laz::SymbolModel& model, std::uint32_t symbol);
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
/// same arguments, from which both build the same io::laz::IntegerModels.
class IntegerEncoder {
public:
    explicit IntegerEncoder(std::uint32_t bits, std::uint32_t contexts = 1,
                            std::uint32_t highBits = 8, std::uint32_t range = 0)
        : m_models(bits, contexts, highBits, range) {}

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

    io::laz::IntegerModels m_models;
    std::uint32_t m_lastClass = 0;
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

/// @file
/// The LAZ range encoder and the integer compressor (see laz_encoder.hpp). Each step is the
/// mirror of a decoder step: where the decoder narrows its interval around the code value it
/// reads, the encoder narrows the same interval around the value it writes, so both lengths
/// stay equal and both renormalise at the same moments.

#include "laz_encoder.hpp"

#include "laz_bytes.hpp"
#include "range_decoder.hpp"

#include <algorithm>
#include <limits>
#include <stdexcept>
#include <string>

namespace terratin::lazrepeat {

namespace {
using io::laz::kMostRawBitsInOneStep;
using io::laz::kRenormaliseBelow;
} // namespace

void RangeEncoder::encodeBit(io::laz::BitModel& model, std::uint32_t bit) {
    const std::uint32_t split = model.zeroLength(m_length);
    if (bit == 0) {
        m_length = split;
    } else {
        advanceBase(split);
        m_length -= split;
    }
    if (m_length < kRenormaliseBelow)
        renormalise();
    model.update(bit);
}

void RangeEncoder::encodeSymbol(io::laz::SymbolModel& model, std::uint32_t symbol) {
    if (symbol >= model.symbols())
        throw std::invalid_argument("RangeEncoder: symbol " + std::to_string(symbol) +
                                    " outside an alphabet of " + std::to_string(model.symbols()));
    const io::laz::Subinterval part = model.subinterval(symbol, m_length);
    advanceBase(part.low);
    m_length = part.length;
    if (m_length < kRenormaliseBelow)
        renormalise();
    model.update(symbol);
}

void RangeEncoder::writeFewBits(std::uint32_t count, std::uint32_t value) {
    m_length >>= count;
    advanceBase(value * m_length);
    if (m_length < kRenormaliseBelow)
        renormalise();
}

void RangeEncoder::writeBits(std::uint32_t count, std::uint32_t value) {
    if (count == 0 || count > 32)
        throw std::invalid_argument("RangeEncoder: " + std::to_string(count) +
                                    " raw bits, outside 1..32");
    if (count < 32 && value >> count != 0)
        throw std::invalid_argument("RangeEncoder: " + std::to_string(value) + " needs more than " +
                                    std::to_string(count) + " bits");
    // Wide fields go as their low 16 bits, then the rest: the order the decoder reads them.
    if (count > kMostRawBitsInOneStep) {
        writeFewBits(16, value & 0xFFFFu);
        writeBits(count - 16, value >> 16);
        return;
    }
    writeFewBits(count, value);
}

void RangeEncoder::writeInt(std::uint32_t value) {
    writeFewBits(16, value & 0xFFFFu);
    writeFewBits(16, value >> 16);
}

void RangeEncoder::writeInt64(std::uint64_t value) {
    writeInt(static_cast<std::uint32_t>(value & 0xFFFFFFFFu));
    writeInt(static_cast<std::uint32_t>(value >> 32));
}

void RangeEncoder::advanceBase(std::uint32_t amount) {
    const std::uint32_t before = m_base;
    m_base += amount;
    if (m_base < before)
        propagateCarry();
}

void RangeEncoder::propagateCarry() {
    // base + length never passes the top of the interval the bytes out so far leave open, so
    // a carry always finds a byte below 0xFF to stop at.
    std::size_t at = m_bytes.size();
    while (at > 0 && m_bytes[at - 1] == std::byte{0xFF})
        m_bytes[--at] = std::byte{0};
    if (at == 0)
        throw std::logic_error("RangeEncoder: a carry ran past the first byte");
    m_bytes[at - 1] = static_cast<std::byte>(std::to_integer<unsigned>(m_bytes[at - 1]) + 1);
}

void RangeEncoder::renormalise() {
    do {
        m_bytes.push_back(static_cast<std::byte>(m_base >> 24));
        m_base <<= 8;
        m_length <<= 8;
    } while (m_length < kRenormaliseBelow);
}

std::vector<std::byte> RangeEncoder::finish() {
    // The code value the decoder reads is base itself, followed by nothing: it lies inside the
    // final interval [base, base + length), whatever the decoder would read after it. The
    // decoder holds 4 bytes more than the encoder has shifted out, so these 4 bytes are
    // exactly what it reads, and it never asks for one past the end.
    for (int shift = 24; shift >= 0; shift -= 8)
        m_bytes.push_back(static_cast<std::byte>((m_base >> shift) & 0xFFu));
    std::vector<std::byte> bytes = std::move(m_bytes);
    m_bytes.clear();
    m_base = 0;
    m_length = 0xFFFFFFFFu;
    return bytes;
}

void IntegerEncoder::reset() {
    m_models.reset();
    m_lastClass = 0;
}

void IntegerEncoder::encode(RangeEncoder& encoder, std::int32_t prediction, std::int32_t value,
                            std::uint32_t context) {
    if (context >= m_models.classModels.size())
        throw std::invalid_argument("IntegerEncoder: context " + std::to_string(context) + " of " +
                                    std::to_string(m_models.classModels.size()));
    // The decoder adds the correction to the prediction modulo 2^32, then folds the sum back
    // into [0, range): the correction is the difference folded into the range's window.
    std::int64_t correction = std::int64_t{value} - std::int64_t{prediction};
    const std::uint32_t range = m_models.valueRange;
    if (range == 0) {
        correction = static_cast<std::int32_t>(static_cast<std::uint32_t>(correction));
    } else {
        const std::int64_t smallest = m_models.smallestCorrection;
        const std::int64_t largest = smallest + std::int64_t{range} - 1;
        if (correction < smallest)
            correction += range;
        else if (correction > largest)
            correction -= range;
    }
    encodeCorrection(encoder, static_cast<std::int32_t>(correction), context);
}

void IntegerEncoder::encodeCorrection(RangeEncoder& encoder, std::int32_t correction,
                                      std::uint32_t context) {
    // Class k holds the corrections -(2^k - 1) .. -2^(k-1) and 2^(k-1) + 1 .. 2^k; class 0
    // holds 0 and 1. k is the bit length of |c| for c <= 0, of c - 1 for c > 0.
    const auto asUnsigned = static_cast<std::uint32_t>(correction);
    std::uint32_t magnitude = correction <= 0 ? 0u - asUnsigned : asUnsigned - 1;
    std::uint32_t k = 0;
    for (; magnitude != 0; magnitude >>= 1)
        ++k;
    m_lastClass = k;
    encoder.encodeSymbol(m_models.classModels[context], k);
    if (k == 0) {
        encoder.encodeBit(m_models.zeroOrOne, asUnsigned);
        return;
    }
    // Class 32 holds -2^31 alone: its class says it all.
    if (k >= 32)
        return;
    // Negative corrections take the positions 0 .. 2^(k-1) - 1, positive ones the rest.
    const std::uint32_t position = correction < 0 ? asUnsigned + ((1u << k) - 1) : asUnsigned - 1;
    io::laz::SymbolModel& positionModel = m_models.positionModels[k - 1];
    if (k <= m_models.modelledPositionBits) {
        encoder.encodeSymbol(positionModel, position);
        return;
    }
    const std::uint32_t lowBits = k - m_models.modelledPositionBits;
    encoder.encodeSymbol(positionModel, position >> lowBits);
    encoder.writeBits(lowBits, position & ((1u << lowBits) - 1));
}

std::vector<std::byte> encodeChunkTableEntries(std::span<const io::laz::ChunkTableEntry> entries,
                                               bool variableChunks) {
    if (entries.empty())
        return {};
    RangeEncoder encoder;
    IntegerEncoder values(32, 2);
    io::laz::ChunkTableEntry previous;
    for (const io::laz::ChunkTableEntry& entry : entries) {
        if (variableChunks)
            values.encode(encoder, static_cast<std::int32_t>(previous.pointCount),
                          static_cast<std::int32_t>(entry.pointCount), 0);
        values.encode(encoder, static_cast<std::int32_t>(previous.byteCount),
                      static_cast<std::int32_t>(entry.byteCount), 1);
        previous = entry;
    }
    return encoder.finish();
}

std::vector<std::byte> encodeChunkTable(std::span<const io::laz::ChunkTableEntry> entries,
                                        bool variableChunks) {
    if (entries.size() > std::numeric_limits<std::uint32_t>::max())
        throw std::invalid_argument("encodeChunkTable: " + std::to_string(entries.size()) +
                                    " chunks, more than a table's 32-bit count holds");
    const std::vector<std::byte> coded = encodeChunkTableEntries(entries, variableChunks);
    constexpr std::size_t kTableHeaderBytes = 8;
    std::vector<std::byte> table(kTableHeaderBytes + coded.size());
    io::laz::storeLe<std::uint32_t>(table.data(), 0);
    io::laz::storeLe<std::uint32_t>(table.data() + 4, static_cast<std::uint32_t>(entries.size()));
    std::copy(coded.begin(), coded.end(), table.begin() + kTableHeaderBytes);
    return table;
}

} // namespace terratin::lazrepeat

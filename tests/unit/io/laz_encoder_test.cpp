// Tests of terratin-lazrepeat's LAZ encoder (tools/lazrepeat/laz_encoder.hpp) against the
// project's own decoder: random bits, symbols of many alphabet sizes, raw fields of 1-32 bits
// and integers of several widths, contexts and ranges, encoded and then decoded by
// RangeDecoder and IntegerDecoder to the same values, the decoder using exactly the bytes
// the encoder wrote; and chunk tables, fixed and variable, that decodeChunkTableEntries reads
// back entry for entry.

#include "chunk_table.hpp"
#include "integer_decoder.hpp"
#include "laz_bytes.hpp"
#include "laz_encoder.hpp"
#include "range_decoder.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <limits>
#include <random>
#include <stdexcept>
#include <utility>
#include <vector>

namespace terratin::lazrepeat {
namespace {

using io::laz::BitModel;
using io::laz::ChunkTableEntry;
using io::laz::IntegerDecoder;
using io::laz::RangeDecoder;
using io::laz::SymbolModel;

/// Starts `decoder` on `bytes` (which must outlive it).
void start(RangeDecoder& decoder, const std::vector<std::byte>& bytes) {
    decoder.start(bytes.data(), bytes.data() + bytes.size());
}

/// The decoder read exactly the encoded stream: every byte, none past its end.
void expectExactRead(const RangeDecoder& decoder, const std::vector<std::byte>& bytes) {
    EXPECT_FALSE(decoder.overran());
    EXPECT_FALSE(decoder.corrupt());
    EXPECT_EQ(decoder.consumed(), bytes.size());
}

/// A symbol of an alphabet of `symbols`, skewed towards the small ones as real streams are
/// (magnitude classes, small corrections), with now and then any symbol at all.
std::uint32_t skewedSymbol(std::mt19937& random, std::uint32_t symbols) {
    if (random() % 8 == 0)
        return static_cast<std::uint32_t>(random() % symbols);
    std::geometric_distribution<std::uint32_t> small(0.3);
    return std::min(small(random), symbols - 1);
}

TEST(LazEncoder, EmptyStreamDecodesToNothingAndReadsFourBytes) {
    RangeEncoder encoder;
    const std::vector<std::byte> bytes = encoder.finish();
    RangeDecoder decoder;
    start(decoder, bytes);
    EXPECT_EQ(bytes.size(), 4u);
    expectExactRead(decoder, bytes);
}

TEST(LazEncoder, SymbolsOfEveryAlphabetSizeRoundTrip) {
    for (const std::uint32_t symbols :
         {2u, 3u, 5u, 16u, 17u, 33u, 64u, 255u, 256u, 257u, 1000u, 2047u, 2048u}) {
        std::mt19937 random(symbols);
        std::vector<std::uint32_t> values(20000);
        for (std::uint32_t& value : values)
            value = skewedSymbol(random, symbols);
        RangeEncoder encoder;
        SymbolModel encoderModel(symbols);
        for (const std::uint32_t value : values)
            encoder.encodeSymbol(encoderModel, value);
        const std::vector<std::byte> bytes = encoder.finish();

        RangeDecoder decoder;
        SymbolModel decoderModel(symbols);
        start(decoder, bytes);
        for (std::size_t i = 0; i < values.size(); ++i)
            ASSERT_EQ(decoder.decodeSymbol(decoderModel), values[i])
                << "symbol " << i << " of an alphabet of " << symbols;
        expectExactRead(decoder, bytes);
    }
}

TEST(LazEncoder, LongRunsOfOneBitOrSymbolRoundTrip) {
    // Runs drive the counts past their limits, so the models halve them again and again.
    RangeEncoder encoder;
    BitModel bits;
    SymbolModel symbols(300);
    for (int i = 0; i < 100000; ++i)
        encoder.encodeBit(bits, i % 5000 == 4999 ? 1u : 0u);
    for (int i = 0; i < 100000; ++i)
        encoder.encodeSymbol(symbols, i % 7000 == 6999 ? 299u : 7u);
    const std::vector<std::byte> bytes = encoder.finish();

    RangeDecoder decoder;
    BitModel decodedBits;
    SymbolModel decodedSymbols(300);
    start(decoder, bytes);
    for (int i = 0; i < 100000; ++i)
        ASSERT_EQ(decoder.decodeBit(decodedBits), i % 5000 == 4999 ? 1u : 0u) << "bit " << i;
    for (int i = 0; i < 100000; ++i)
        ASSERT_EQ(decoder.decodeSymbol(decodedSymbols), i % 7000 == 6999 ? 299u : 7u)
            << "symbol " << i;
    expectExactRead(decoder, bytes);
}

/// One step of a mixed stream: which call, on which model, with which value.
struct Step {
    enum Kind { Bit, Symbol, Bits, Short, Int, Int64 } kind = Bit;
    std::uint32_t model = 0;
    std::uint32_t count = 0;
    std::uint64_t value = 0;
};

std::vector<Step> mixedSteps(std::mt19937& random, const std::vector<std::uint32_t>& alphabets) {
    std::vector<Step> steps(30000);
    for (Step& step : steps) {
        step.kind = static_cast<Step::Kind>(random() % 6);
        switch (step.kind) {
        case Step::Bit:
            step.model = static_cast<std::uint32_t>(random() % 3);
            // Model m gives 1 with probability (m + 1) / 8.
            step.value = random() % 8 <= step.model ? 1 : 0;
            break;
        case Step::Symbol:
            step.model = static_cast<std::uint32_t>(random() % alphabets.size());
            step.value = skewedSymbol(random, alphabets[step.model]);
            break;
        case Step::Bits:
            step.count = 1 + static_cast<std::uint32_t>(random() % 32);
            step.value = random() & (step.count == 32 ? 0xFFFFFFFFu : (1u << step.count) - 1);
            break;
        case Step::Short:
            step.value = random() & 0xFFFFu;
            break;
        case Step::Int:
            step.value = random();
            break;
        case Step::Int64:
            step.value = (std::uint64_t{random()} << 32) | random();
            break;
        }
    }
    return steps;
}

std::vector<std::byte> encodeSteps(const std::vector<Step>& steps,
                                   const std::vector<std::uint32_t>& alphabets) {
    RangeEncoder encoder;
    std::vector<BitModel> bitModels(3);
    std::vector<SymbolModel> symbolModels;
    for (const std::uint32_t symbols : alphabets)
        symbolModels.emplace_back(symbols);
    for (const Step& step : steps) {
        const auto value32 = static_cast<std::uint32_t>(step.value);
        switch (step.kind) {
        case Step::Bit:
            encoder.encodeBit(bitModels[step.model], value32);
            break;
        case Step::Symbol:
            encoder.encodeSymbol(symbolModels[step.model], value32);
            break;
        case Step::Bits:
            encoder.writeBits(step.count, value32);
            break;
        case Step::Short:
            encoder.writeShort(value32);
            break;
        case Step::Int:
            encoder.writeInt(value32);
            break;
        case Step::Int64:
            encoder.writeInt64(step.value);
            break;
        }
    }
    return encoder.finish();
}

std::uint64_t decodeStep(RangeDecoder& decoder, const Step& step, std::vector<BitModel>& bitModels,
                         std::vector<SymbolModel>& symbolModels) {
    switch (step.kind) {
    case Step::Bit:
        return decoder.decodeBit(bitModels[step.model]);
    case Step::Symbol:
        return decoder.decodeSymbol(symbolModels[step.model]);
    case Step::Bits:
        return decoder.readBits(step.count);
    case Step::Short:
        return decoder.readShort();
    case Step::Int:
        return decoder.readInt();
    case Step::Int64:
        return decoder.readInt64();
    }
    return 0;
}

TEST(LazEncoder, MixedBitsSymbolsAndRawFieldsRoundTrip) {
    const std::vector<std::uint32_t> alphabets{2, 6, 33, 256, 2048};
    for (const unsigned seed : {1u, 2u, 3u}) {
        std::mt19937 random(seed);
        const std::vector<Step> steps = mixedSteps(random, alphabets);
        const std::vector<std::byte> bytes = encodeSteps(steps, alphabets);

        RangeDecoder decoder;
        std::vector<BitModel> bitModels(3);
        std::vector<SymbolModel> symbolModels;
        for (const std::uint32_t symbols : alphabets)
            symbolModels.emplace_back(symbols);
        start(decoder, bytes);
        for (std::size_t i = 0; i < steps.size(); ++i)
            ASSERT_EQ(decodeStep(decoder, steps[i], bitModels, symbolModels), steps[i].value)
                << "step " << i << " (kind " << steps[i].kind << ") of seed " << seed;
        expectExactRead(decoder, bytes);
    }
}

/// An integer coder's shape: IntegerDecoder's constructor arguments.
struct IntegerShape {
    std::uint32_t bits;
    std::uint32_t contexts;
    std::uint32_t highBits;
    std::uint32_t range;
};

/// Values and predictions inside the shape's domain, with the corrections at its edges.
std::vector<std::pair<std::int32_t, std::int32_t>> predictedValues(std::mt19937& random,
                                                                   const IntegerShape& shape) {
    const std::uint64_t domain = shape.range != 0                       ? shape.range
                                 : (shape.bits != 0 && shape.bits < 32) ? 1ull << shape.bits
                                                                        : 1ull << 32;
    const auto any = [&] { return static_cast<std::int32_t>(std::uint64_t{random()} % domain); };
    std::vector<std::pair<std::int32_t, std::int32_t>> pairs;
    std::int32_t previous = 0;
    for (int i = 0; i < 6000; ++i) {
        std::int32_t value = any();
        switch (i % 4) {
        case 0: // close to the prediction, as in real streams
            value = static_cast<std::int32_t>(
                (std::uint64_t(std::uint32_t(previous)) + random() % 5 + domain - 2) % domain);
            break;
        case 1: // the largest jumps either way
            value = static_cast<std::int32_t>(
                (std::uint64_t(std::uint32_t(previous)) + domain / 2 + (random() % 2)) % domain);
            break;
        default:
            break;
        }
        pairs.emplace_back(previous, value);
        previous = random() % 3 == 0 ? any() : value;
    }
    return pairs;
}

TEST(LazEncoder, IntegersOfSeveralWidthsContextsAndRangesRoundTrip) {
    const std::vector<IntegerShape> shapes{
        {1, 1, 8, 0},   {2, 2, 8, 0},  {8, 3, 8, 0},    {12, 1, 4, 0},    {16, 2, 8, 0},
        {17, 4, 8, 0},  {24, 1, 8, 0}, {31, 2, 8, 0},   {32, 2, 8, 0},    {0, 1, 8, 0},
        {32, 3, 11, 0}, {0, 2, 8, 5},  {0, 1, 8, 1000}, {0, 2, 8, 65536}, {0, 1, 6, 1u << 31}};
    for (const IntegerShape& shape : shapes) {
        std::mt19937 random(shape.bits * 131 + shape.range + shape.contexts);
        const auto pairs = predictedValues(random, shape);
        RangeEncoder encoder;
        IntegerEncoder values(shape.bits, shape.contexts, shape.highBits, shape.range);
        std::vector<std::uint32_t> classes;
        for (std::size_t i = 0; i < pairs.size(); ++i) {
            values.encode(encoder, pairs[i].first, pairs[i].second,
                          static_cast<std::uint32_t>(i % shape.contexts));
            classes.push_back(values.lastClass());
        }
        const std::vector<std::byte> bytes = encoder.finish();

        RangeDecoder decoder;
        IntegerDecoder decoded(shape.bits, shape.contexts, shape.highBits, shape.range);
        start(decoder, bytes);
        for (std::size_t i = 0; i < pairs.size(); ++i) {
            ASSERT_EQ(decoded.decode(decoder, pairs[i].first,
                                     static_cast<std::uint32_t>(i % shape.contexts)),
                      pairs[i].second)
                << "value " << i << " of bits " << shape.bits << ", range " << shape.range;
            ASSERT_EQ(decoded.lastClass(), classes[i]) << "value " << i;
        }
        expectExactRead(decoder, bytes);
    }
}

TEST(LazEncoder, ThirtyTwoBitCorrectionsAtTheExtremesRoundTrip) {
    constexpr std::int32_t kMin = std::numeric_limits<std::int32_t>::min();
    constexpr std::int32_t kMax = std::numeric_limits<std::int32_t>::max();
    const std::vector<std::pair<std::int32_t, std::int32_t>> pairs{
        {0, kMin}, {0, kMax}, {kMin, kMax}, {kMax, kMin}, {-1, kMax}, {1, kMin},
        {0, 0},    {0, 1},    {5, 4},       {kMax, kMax}, {0, -1},    {kMin, 0}};
    RangeEncoder encoder;
    IntegerEncoder values(32, 1);
    for (const auto& [prediction, value] : pairs)
        values.encode(encoder, prediction, value);
    const std::vector<std::byte> bytes = encoder.finish();
    RangeDecoder decoder;
    IntegerDecoder decoded(32, 1);
    start(decoder, bytes);
    for (const auto& [prediction, value] : pairs)
        EXPECT_EQ(decoded.decode(decoder, prediction), value) << prediction << " -> " << value;
    expectExactRead(decoder, bytes);
}

TEST(LazEncoder, RefusesWhatNoDecoderCouldRead) {
    RangeEncoder encoder;
    SymbolModel model(4);
    EXPECT_THROW(encoder.encodeSymbol(model, 4), std::invalid_argument);
    EXPECT_THROW(encoder.writeBits(0, 0), std::invalid_argument);
    EXPECT_THROW(encoder.writeBits(33, 0), std::invalid_argument);
    EXPECT_THROW(encoder.writeBits(3, 8), std::invalid_argument);
    IntegerEncoder values(16, 2);
    EXPECT_THROW(values.encode(encoder, 0, 1, 2), std::invalid_argument);
}

std::vector<ChunkTableEntry> randomEntries(std::mt19937& random, std::size_t count, bool variable) {
    std::vector<ChunkTableEntry> entries(count);
    for (ChunkTableEntry& entry : entries) {
        entry.pointCount = variable ? static_cast<std::uint32_t>(random() % 100000) : 0;
        entry.byteCount = static_cast<std::uint32_t>(100000 + random() % 2000000);
    }
    return entries;
}

void expectSameEntries(const std::vector<ChunkTableEntry>& actual,
                       const std::vector<ChunkTableEntry>& expected) {
    ASSERT_EQ(actual.size(), expected.size());
    for (std::size_t i = 0; i < actual.size(); ++i) {
        EXPECT_EQ(actual[i].pointCount, expected[i].pointCount) << "entry " << i;
        EXPECT_EQ(actual[i].byteCount, expected[i].byteCount) << "entry " << i;
    }
}

TEST(LazEncoder, ChunkTablesDecodeToTheSameEntries) {
    std::mt19937 random(7);
    for (const bool variable : {false, true}) {
        for (const std::size_t count : {1u, 2u, 11u, 429u, 5000u}) {
            const std::vector<ChunkTableEntry> entries = randomEntries(random, count, variable);
            const std::vector<std::byte> coded = encodeChunkTableEntries(entries, variable);
            expectSameEntries(io::laz::decodeChunkTableEntries(
                                  coded, static_cast<std::uint32_t>(count), variable, "test"),
                              entries);
            // In a file the decoder is handed whatever follows the table too.
            std::vector<std::byte> followed = coded;
            followed.resize(coded.size() + 64, std::byte{0xA5});
            expectSameEntries(io::laz::decodeChunkTableEntries(
                                  followed, static_cast<std::uint32_t>(count), variable, "test"),
                              entries);
        }
    }
}

TEST(LazEncoder, ChunkTableEntriesAtTheLimitsRoundTrip) {
    constexpr std::uint32_t kMax = std::numeric_limits<std::uint32_t>::max();
    const std::vector<ChunkTableEntry> entries{
        {50000, 250000}, {50000, 250000}, {1, 40}, {kMax, kMax}, {0, 1}, {kMax, 1}, {7, kMax}};
    const std::vector<std::byte> coded = encodeChunkTableEntries(entries, true);
    expectSameEntries(io::laz::decodeChunkTableEntries(
                          coded, static_cast<std::uint32_t>(entries.size()), true, "test"),
                      entries);
}

TEST(LazEncoder, ChunkTableHasVersionCountAndCodedEntries) {
    const std::vector<ChunkTableEntry> entries{{0, 1000}, {0, 2000}, {0, 1500}};
    const std::vector<std::byte> table = encodeChunkTable(entries, false);
    ASSERT_GE(table.size(), 8u);
    EXPECT_EQ(io::laz::loadLe<std::uint32_t>(table.data()), 0u);
    EXPECT_EQ(io::laz::loadLe<std::uint32_t>(table.data() + 4), 3u);
    const std::vector<std::byte> coded(table.begin() + 8, table.end());
    EXPECT_EQ(coded, encodeChunkTableEntries(entries, false));
    EXPECT_TRUE(encodeChunkTableEntries({}, true).empty());
    EXPECT_EQ(encodeChunkTable({}, true).size(), 8u);
}

} // namespace
} // namespace terratin::lazrepeat

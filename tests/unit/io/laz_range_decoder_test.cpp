// Tests of the LAZ range decoder, its models and the integer decoder, against
// terratin-lazrepeat's encoder (tools/lazrepeat/laz_encoder.hpp), which codes with these same
// models: random symbols of every alphabet size the format uses, bits, raw fields of 1-32 bits,
// and integers with corrections up to the full 32-bit range, decoded back exactly and with the
// encoder's byte count. The real files (laz_decode_test) prove the rules; these prove the
// mechanics at the edges files rarely reach.

#include "integer_decoder.hpp"
#include "laz_encoder.hpp"
#include "range_decoder.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <limits>
#include <random>
#include <stdexcept>
#include <vector>

namespace terratin::io::laz {
namespace {

using lazrepeat::IntegerEncoder;
using lazrepeat::RangeEncoder;

std::uint32_t draw(std::mt19937& random) {
    return static_cast<std::uint32_t>(random());
}

/// A skewed random symbol of an alphabet of n, so that the models adapt away from uniform.
std::uint32_t skewed(std::mt19937& random, std::uint32_t n) {
    std::geometric_distribution<std::uint32_t> small(0.2);
    return draw(random) % 4 == 0 ? draw(random) % n : std::min(small(random), n - 1);
}

TEST(LazRangeDecoder, DecodesSymbolsBitsAndRawFieldsAsEncoded) {
    const std::vector<std::uint32_t> alphabets{2, 3, 6, 16, 17, 33, 64, 128, 256, 512, 516, 2048};
    std::vector<SymbolModel> encoderModels;
    std::vector<SymbolModel> decoderModels;
    for (const std::uint32_t n : alphabets) {
        encoderModels.emplace_back(n);
        decoderModels.emplace_back(n);
    }
    BitModel encoderBit;
    BitModel decoderBit;
    std::mt19937 random(7);
    struct Step {
        int kind;
        std::size_t model;
        std::uint32_t width;
        std::uint64_t value;
    };
    std::vector<Step> steps;
    RangeEncoder encoder;
    for (int i = 0; i < 200000; ++i) {
        const int kind = static_cast<int>(draw(random) % 8);
        if (kind < 4) {
            const std::size_t m = draw(random) % alphabets.size();
            const std::uint32_t s = skewed(random, alphabets[m]);
            encoder.encodeSymbol(encoderModels[m], s);
            steps.push_back({0, m, 0, s});
        } else if (kind < 6) {
            const std::uint32_t b = draw(random) % 5 == 0 ? 1 : 0;
            encoder.encodeBit(encoderBit, b);
            steps.push_back({1, 0, 0, b});
        } else if (kind == 6) {
            const std::uint32_t width = 1 + draw(random) % 32;
            const std::uint32_t value =
                width == 32 ? draw(random) : draw(random) & ((1u << width) - 1);
            encoder.writeBits(width, value);
            steps.push_back({2, 0, width, value});
        } else {
            const std::uint64_t value = (std::uint64_t{draw(random)} << 32) | draw(random);
            encoder.writeBits(32, static_cast<std::uint32_t>(value));
            encoder.writeBits(32, static_cast<std::uint32_t>(value >> 32));
            steps.push_back({3, 0, 64, value});
        }
    }
    const std::vector<std::byte> bytes = encoder.finish();
    RangeDecoder decoder;
    decoder.start(bytes.data(), bytes.data() + bytes.size());
    for (std::size_t i = 0; i < steps.size(); ++i) {
        const Step& step = steps[i];
        std::uint64_t got = 0;
        switch (step.kind) {
        case 0:
            got = decoder.decodeSymbol(decoderModels[step.model]);
            break;
        case 1:
            got = decoder.decodeBit(decoderBit);
            break;
        case 2:
            got = decoder.readBits(step.width);
            break;
        default:
            got = decoder.readInt64();
            break;
        }
        ASSERT_EQ(got, step.value) << "step " << i << " of kind " << step.kind;
    }
    EXPECT_FALSE(decoder.overran());
    EXPECT_FALSE(decoder.corrupt());
    EXPECT_EQ(decoder.consumed(), bytes.size());
}

TEST(LazRangeDecoder, IntegersRoundTripAtEveryWidthAndContext) {
    struct Case {
        std::uint32_t bits, contexts, highBits;
    };
    for (const Case c :
         {Case{32, 3, 8}, Case{16, 4, 8}, Case{8, 6, 8}, Case{32, 2, 11}, Case{1, 1, 8}}) {
        IntegerEncoder encoderSide(c.bits, c.contexts, c.highBits);
        IntegerDecoder decoderSide(c.bits, c.contexts, c.highBits);
        std::mt19937 random(c.bits * 100 + c.contexts);
        const std::uint32_t mask = c.bits >= 32 ? 0xFFFFFFFFu : (1u << c.bits) - 1;
        struct Value {
            std::int32_t prediction, value;
            std::uint32_t context;
        };
        std::vector<Value> values;
        RangeEncoder encoder;
        for (int i = 0; i < 50000; ++i) {
            // Mostly small corrections, some of every size, and the extremes.
            const auto prediction = static_cast<std::int32_t>(draw(random) & mask);
            std::uint32_t delta = draw(random) % 3 == 0 ? draw(random) : draw(random) % 64;
            if (i % 1000 == 0)
                delta = 0x80000000u;
            const auto value =
                static_cast<std::int32_t>((static_cast<std::uint32_t>(prediction) + delta) & mask);
            const std::uint32_t context = draw(random) % c.contexts;
            encoderSide.encode(encoder, prediction, value, context);
            values.push_back({prediction, value, context});
        }
        const std::vector<std::byte> bytes = encoder.finish();
        RangeDecoder decoder;
        decoder.start(bytes.data(), bytes.data() + bytes.size());
        for (std::size_t i = 0; i < values.size(); ++i)
            ASSERT_EQ(decoderSide.decode(decoder, values[i].prediction, values[i].context),
                      values[i].value)
                << c.bits << "-bit value " << i;
        EXPECT_EQ(decoder.consumed(), bytes.size()) << c.bits << " bits";
        EXPECT_FALSE(decoder.overran() || decoder.corrupt());
    }
}

TEST(LazRangeDecoder, ReportsAStreamThatEndsTooSoon) {
    SymbolModel encoderModel(256);
    RangeEncoder encoder;
    std::mt19937 random(3);
    for (int i = 0; i < 5000; ++i)
        encoder.encodeSymbol(encoderModel, draw(random) % 256);
    std::vector<std::byte> bytes = encoder.finish();
    bytes.resize(bytes.size() / 2);
    SymbolModel model(256);
    RangeDecoder decoder;
    decoder.start(bytes.data(), bytes.data() + bytes.size());
    for (int i = 0; i < 5000; ++i)
        (void)decoder.decodeSymbol(model);
    EXPECT_TRUE(decoder.overran());
    EXPECT_GT(decoder.consumed(), bytes.size());
}

TEST(LazRangeDecoder, AnEmptyOrHostileStreamStaysInBounds) {
    // No bytes at all, then bytes that claim the largest code value: decoding goes on
    // (garbage) without reading outside the range, and says so.
    for (const std::vector<std::byte>& bytes :
         {std::vector<std::byte>{}, std::vector<std::byte>(64, std::byte{0xFF})}) {
        RangeDecoder decoder;
        decoder.start(bytes.data(), bytes.data() + bytes.size());
        SymbolModel big(2048);
        SymbolModel small(5);
        BitModel bit;
        for (int i = 0; i < 1000; ++i) {
            EXPECT_LT(decoder.decodeSymbol(big), 2048u);
            EXPECT_LT(decoder.decodeSymbol(small), 5u);
            EXPECT_LT(decoder.decodeBit(bit), 2u);
            EXPECT_LT(decoder.readBits(7), 128u);
        }
        EXPECT_TRUE(decoder.overran());
    }
}

TEST(LazRangeDecoder, SymbolAtFindsTheSymbolOfEachSubinterval) {
    // The parts tile the interval, none empty, and the search the decoder makes leads from
    // either end of a part back to its symbol: with and without the lookup table, after the
    // counts have moved away from uniform, at the shortest and the longest interval.
    std::mt19937 random(11);
    for (const std::uint32_t n : {2u, 5u, 16u, 17u, 300u, 2048u}) {
        SymbolModel model(n);
        for (int i = 0; i < 20000; ++i)
            model.update(skewed(random, n));
        for (const std::uint32_t length : {kRenormaliseBelow, 0xFFFFFFFFu}) {
            std::uint32_t end = 0;
            for (std::uint32_t s = 0; s < n; ++s) {
                const Subinterval part = model.subinterval(s, length);
                ASSERT_EQ(part.low, end) << "symbol " << s << " of " << n;
                ASSERT_GT(part.length, 0u) << "symbol " << s << " of " << n;
                EXPECT_EQ(model.symbolAt(part.low, length), s) << n << " symbols";
                EXPECT_EQ(model.symbolAt(part.low + part.length - 1, length), s) << n << " symbols";
                end = part.low + part.length;
            }
            EXPECT_EQ(end, length) << n << " symbols";
        }
    }
}

TEST(LazRangeDecoder, SymbolModelsHoldTwoTo2048Symbols) {
    EXPECT_THROW(SymbolModel(1), std::invalid_argument);
    EXPECT_THROW(SymbolModel(2049), std::invalid_argument);
    EXPECT_NO_THROW(SymbolModel(2));
    EXPECT_NO_THROW(SymbolModel(2048));
}

} // namespace
} // namespace terratin::io::laz

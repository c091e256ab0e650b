// Tests of the LAZ range decoder, its models and the integer decoder, against an encoder
// written here from the same published rules (FastAC as LASzip adapts it): random symbols of
// every alphabet size the format uses, bits, raw fields of 1-32 bits, and integers with
// corrections up to the full 32-bit range, decoded back exactly and with the encoder's byte
// count. The real files (laz_decode_test) prove the rules; these prove the mechanics at the
// edges files rarely reach.

#include "integer_decoder.hpp"
#include "range_decoder.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <limits>
#include <random>
#include <stdexcept>
#include <vector>

namespace terratin::io::laz {
namespace {

constexpr std::uint32_t kMinLength = 0x01000000u;

/// The adaptive symbol model, encoder side: counts, a 15-bit cumulative distribution, the
/// same refresh schedule, searched linearly (the decoder's lookup table is not needed here).
struct TestSymbolModel {
    explicit TestSymbolModel(std::uint32_t n) : counts(n, 1), cumulative(n) {
        cycle = n;
        refresh();
        cycle = until = (n + 6) / 2;
    }
    void refresh() {
        total += cycle;
        if (total > (1u << 15)) {
            total = 0;
            for (auto& c : counts)
                total += c = (c + 1) / 2;
        }
        const std::uint32_t scale = 0x80000000u / total;
        std::uint32_t sum = 0;
        for (std::size_t s = 0; s < counts.size(); ++s) {
            cumulative[s] = (scale * sum) >> 16;
            sum += counts[s];
        }
        cycle = std::min<std::uint32_t>(5 * cycle / 4,
                                        (static_cast<std::uint32_t>(counts.size()) + 6) * 8);
        until = cycle;
    }
    std::vector<std::uint32_t> counts;
    std::vector<std::uint32_t> cumulative;
    std::uint32_t total = 0, cycle = 0, until = 0;
};

struct TestBitModel {
    void refresh() {
        total += cycle;
        if (total > (1u << 13)) {
            total = (total + 1) / 2;
            zeros = (zeros + 1) / 2;
            if (zeros == total)
                ++total;
        }
        probability = (zeros * (0x80000000u / total)) >> 18;
        cycle = std::min<std::uint32_t>(5 * cycle / 4, 64);
        until = cycle;
    }
    std::uint32_t zeros = 1, total = 2, probability = 1u << 12, cycle = 4, until = 4;
};

class TestEncoder {
public:
    void symbol(TestSymbolModel& m, std::uint32_t s) {
        const std::uint32_t before = m_base;
        if (s + 1 == m.counts.size()) {
            const std::uint32_t low = m.cumulative[s] * (m_length >> 15);
            m_base += low;
            m_length -= low;
        } else {
            m_length >>= 15;
            const std::uint32_t low = m.cumulative[s] * m_length;
            m_base += low;
            m_length = m.cumulative[s + 1] * m_length - low;
        }
        settle(before);
        ++m.counts[s];
        if (--m.until == 0)
            m.refresh();
    }
    void bit(TestBitModel& m, std::uint32_t b) {
        const std::uint32_t split = m.probability * (m_length >> 13);
        const std::uint32_t before = m_base;
        if (b == 0) {
            m_length = split;
            ++m.zeros;
        } else {
            m_base += split;
            m_length -= split;
        }
        settle(before);
        if (--m.until == 0)
            m.refresh();
    }
    void raw(std::uint32_t count, std::uint32_t value) {
        if (count > 19) {
            raw(16, value & 0xFFFFu);
            raw(count - 16, value >> 16);
            return;
        }
        const std::uint32_t before = m_base;
        m_length >>= count;
        m_base += value * m_length;
        settle(before);
    }
    std::vector<std::byte> finish() {
        const std::uint32_t before = m_base;
        const bool threeZeros = m_length > 2 * kMinLength;
        m_base += threeZeros ? kMinLength : kMinLength >> 1;
        m_length = threeZeros ? kMinLength >> 1 : kMinLength >> 9;
        if (before > m_base)
            carry();
        shiftOut();
        m_bytes.resize(m_bytes.size() + (threeZeros ? 3 : 2), std::byte{0});
        return m_bytes;
    }

private:
    void settle(std::uint32_t before) {
        if (before > m_base)
            carry();
        if (m_length < kMinLength)
            shiftOut();
    }
    void carry() {
        std::size_t i = m_bytes.size();
        while (m_bytes[--i] == std::byte{0xFF})
            m_bytes[i] = std::byte{0};
        m_bytes[i] = static_cast<std::byte>(std::to_integer<unsigned>(m_bytes[i]) + 1);
    }
    void shiftOut() {
        do {
            m_bytes.push_back(static_cast<std::byte>(m_base >> 24));
            m_base <<= 8;
        } while ((m_length <<= 8) < kMinLength);
    }
    std::uint32_t m_base = 0;
    std::uint32_t m_length = 0xFFFFFFFFu;
    std::vector<std::byte> m_bytes;
};

/// The integer compressor, encoder side, for `bits`-bit values and `contexts` contexts.
class TestIntegerEncoder {
public:
    TestIntegerEncoder(std::uint32_t bits, std::uint32_t contexts, std::uint32_t highBits = 8)
        : m_highBits(highBits) {
        m_bits = bits >= 1 && bits < 32 ? bits : 32;
        m_range = m_bits < 32 ? (std::uint64_t{1} << m_bits) : 0;
        for (std::uint32_t c = 0; c < contexts; ++c)
            m_classes.emplace_back(m_bits + 1);
        for (std::uint32_t k = 1; k <= m_bits; ++k)
            m_positions.emplace_back(1u << std::min(k, highBits));
    }
    void encode(TestEncoder& out, std::int32_t prediction, std::int32_t value,
                std::uint32_t context) {
        std::int64_t correction = std::int64_t{value} - prediction;
        if (m_range != 0) {
            const auto half = static_cast<std::int64_t>(m_range / 2);
            if (correction < -half)
                correction += static_cast<std::int64_t>(m_range);
            else if (correction > half - 1)
                correction -= static_cast<std::int64_t>(m_range);
        } else {
            correction = static_cast<std::int32_t>(static_cast<std::uint32_t>(correction));
        }
        const auto c = static_cast<std::int32_t>(correction);
        std::uint32_t magnitude =
            c <= 0 ? 0u - static_cast<std::uint32_t>(c) : static_cast<std::uint32_t>(c) - 1;
        std::uint32_t k = 0;
        for (; magnitude != 0; magnitude >>= 1)
            ++k;
        out.symbol(m_classes[context], k);
        if (k == 0) {
            out.bit(m_zeroOrOne, static_cast<std::uint32_t>(c));
            return;
        }
        if (k >= 32)
            return;
        const std::uint32_t position = c < 0 ? static_cast<std::uint32_t>(c) + ((1u << k) - 1)
                                             : static_cast<std::uint32_t>(c) - 1;
        if (k <= m_highBits) {
            out.symbol(m_positions[k - 1], position);
        } else {
            const std::uint32_t low = k - m_highBits;
            out.symbol(m_positions[k - 1], position >> low);
            out.raw(low, position & ((1u << low) - 1));
        }
    }

private:
    std::uint32_t m_bits = 32, m_highBits = 8;
    std::uint64_t m_range = 0;
    std::vector<TestSymbolModel> m_classes, m_positions;
    TestBitModel m_zeroOrOne;
};

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
    std::vector<TestSymbolModel> encoderModels;
    std::vector<SymbolModel> decoderModels;
    for (const std::uint32_t n : alphabets) {
        encoderModels.emplace_back(n);
        decoderModels.emplace_back(n);
    }
    TestBitModel encoderBit;
    BitModel decoderBit;
    std::mt19937 random(7);
    struct Step {
        int kind;
        std::size_t model;
        std::uint32_t width;
        std::uint64_t value;
    };
    std::vector<Step> steps;
    TestEncoder encoder;
    for (int i = 0; i < 200000; ++i) {
        const int kind = static_cast<int>(draw(random) % 8);
        if (kind < 4) {
            const std::size_t m = draw(random) % alphabets.size();
            const std::uint32_t s = skewed(random, alphabets[m]);
            encoder.symbol(encoderModels[m], s);
            steps.push_back({0, m, 0, s});
        } else if (kind < 6) {
            const std::uint32_t b = draw(random) % 5 == 0 ? 1 : 0;
            encoder.bit(encoderBit, b);
            steps.push_back({1, 0, 0, b});
        } else if (kind == 6) {
            const std::uint32_t width = 1 + draw(random) % 32;
            const std::uint32_t value =
                width == 32 ? draw(random) : draw(random) & ((1u << width) - 1);
            encoder.raw(width, value);
            steps.push_back({2, 0, width, value});
        } else {
            const std::uint64_t value = (std::uint64_t{draw(random)} << 32) | draw(random);
            encoder.raw(32, static_cast<std::uint32_t>(value));
            encoder.raw(32, static_cast<std::uint32_t>(value >> 32));
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
        TestIntegerEncoder encoderSide(c.bits, c.contexts, c.highBits);
        IntegerDecoder decoderSide(c.bits, c.contexts, c.highBits);
        std::mt19937 random(c.bits * 100 + c.contexts);
        const std::uint32_t mask = c.bits >= 32 ? 0xFFFFFFFFu : (1u << c.bits) - 1;
        struct Value {
            std::int32_t prediction, value;
            std::uint32_t context;
        };
        std::vector<Value> values;
        TestEncoder encoder;
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
    TestSymbolModel encoderModel(256);
    TestEncoder encoder;
    std::mt19937 random(3);
    for (int i = 0; i < 5000; ++i)
        encoder.symbol(encoderModel, draw(random) % 256);
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

TEST(LazRangeDecoder, SymbolModelsHoldTwoTo2048Symbols) {
    EXPECT_THROW(SymbolModel(1), std::invalid_argument);
    EXPECT_THROW(SymbolModel(2049), std::invalid_argument);
    EXPECT_NO_THROW(SymbolModel(2));
    EXPECT_NO_THROW(SymbolModel(2048));
}

} // namespace
} // namespace terratin::io::laz
